#!/usr/bin/env bash
# make bench: strong scaling of stray-mpi from 1 to 2 ranks on this
# machine and the per-rank efficiency, as ratios of times measured in
# this run (best of 3 each: the machine is shared), against the
# one-process tracer as baseline; and the communication per piece
# (stray-mpi --stats).  Times are the traces' own ("seconds" of --json:
# the trace, without MPI start-up and scene building), plus the whole
# command's wall time for the start-up cost.
set -eu
build=${STRAY_BUILD:-build}
stray=$build/bin/stray
smpi=$build/bin/stray-mpi
rays=${BENCH_MPI_RAYS:-600000}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
args=(trace --scene ref4 --rays "$rays" --seed 3 --json)

# best_of CMD...: prints "trace_seconds wall_seconds" (minimum of 3 runs)
best_of() {
	local best="" wall="" i t0 t1 s w
	for i in 1 2 3; do
		t0=$(date +%s.%N)
		"$@" --out "$tmp/c.csv" > "$tmp/j.json" 2> "$tmp/e.txt"
		t1=$(date +%s.%N)
		s=$(sed -n 's/.*"seconds":[[:space:]]*\([0-9.e+-]*\).*/\1/p' "$tmp/j.json")
		w=$(awk -v a="$t1" -v b="$t0" 'BEGIN { print a - b }')
		best=$(awk -v a="$s" -v b="${best:-1e99}" 'BEGIN { print (a < b ? a : b) }')
		wall=$(awk -v a="$w" -v b="${wall:-1e99}" 'BEGIN { print (a < b ? a : b) }')
	done
	echo "$best $wall"
}

read -r t_ser w_ser < <(best_of "$stray" "${args[@]}" --threads 1)
cp "$tmp/c.csv" "$tmp/serial.csv"
read -r t_thr w_thr < <(best_of "$stray" "${args[@]}" --threads 2)
read -r t_1 w_1 < <(best_of mpirun -n 1 "$smpi" --stats "${args[@]}")
read -r t_2 w_2 < <(best_of mpirun -n 2 "$smpi" --stats "${args[@]}")
cmp -s "$tmp/c.csv" "$tmp/serial.csv" && same=yes || same=NO
stats=$(grep 'stray-mpi: stats' "$tmp/e.txt" | tail -n 1)
field() { echo "$stats" | sed -n "s/.* $1 \([0-9.]*\).*/\1/p"; }

r() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a / b }'; }
echo "ref4, $rays paths, default angles; best of 3; 2 cores shared"
echo "baseline: stray trace --threads 1: ${t_ser} s (trace), ${w_ser} s (command)"
echo "stray-mpi 1 rank / baseline (farm overhead):     $(r "$t_1" "$t_ser")"
echo "strong scaling, speedup 1 -> 2 ranks (t1/t2):     $(r "$t_1" "$t_2")"
echo "per-rank efficiency (speedup / 2):               $(r "$(r "$t_1" "$t_2")" 2)"
echo "2 ranks vs baseline (t_baseline/t2):             $(r "$t_ser" "$t_2")"
echo "2 threads vs baseline (same machine, no MPI):     $(r "$t_ser" "$t_thr")"
echo "with start-up, 2 ranks vs baseline (command wall): $(r "$w_ser" "$w_2")"
echo "2-rank curve identical to the 1-process curve:    $same"
echo "communication (2 ranks): main pass $(field bytes_per_remote_piece) bytes per piece" \
     "($(field pieces) pieces, $(field remote_pieces) remote);" \
     "pilot $(field pilot_bytes_per_remote_piece) bytes per piece;" \
     "job + guide $(field job_bytes) bytes per trace"
