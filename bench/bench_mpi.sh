#!/usr/bin/env bash
# make bench: stray-mpi on this machine and its cost model.
# 1. Strong scaling 1 -> 2 ranks of a 127-angle ref4 curve to ~1 % (the
#    one-process tracer, 1 and 2 threads, as baseline), from ALTERNATING
#    runs (t1, mpi1, mpi2, t2, t1, ...; BENCH_PAIRS rounds, default 3):
#    median ratio and min-max, so load from others hits both sides.
# 2. The cost model's inputs (bench/mpi_model.awk): fixed, per-piece and
#    per-path costs fitted to five 1-rank runs (R, R/4 with 1 and 4 angle
#    chunks, 12 800 paths, a 1152-piece trace), the latency of a remote
#    piece from that many-piece trace at 1 and 2 ranks, and a 64-design sweep (its designs farmed together) at 1 and
#    2 ranks, alternated: its --stats line gives the scene builds, rank
#    0's start and per-design work (curve kept), bytes per piece.
# 3. The model's prediction for 2 ranks against the measurement (curve
#    and sweep; raw, and corrected for the load measured in each run), and
#    its efficiency at 16, 64, 256 ranks with what limits it: the curve,
#    and the sweep at 1.5 M (each design to ~1 %), 300 000 and
#    BENCH_MPI_SWEEP_RAYS (default 30 000) paths per design.
# Times are the traces' own ("seconds" of --json / --stats: without MPI
# start-up) unless "command" says otherwise.
set -eu
. bench/alt.sh
build=${STRAY_BUILD:-build}
stray=$build/bin/stray
smpi=$build/bin/stray-mpi
rays=${BENCH_MPI_RAYS:-1500000}
srays=${BENCH_MPI_SWEEP_RAYS:-30000}
angles=0:30:5,30:90:0.5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=${BENCH_TMP:-$(mktemp -d)}; [ -n "${BENCH_TMP:-}" ] || trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
sub() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.6g", a - b }'; }
div() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.6g", a / b }'; }

# The load of others during a run, in cores: the machine's busy time
# (/proc/stat: user, nice, system, irq, softirq and steal, the time a
# virtual machine's host took) less the run's own CPU time, over its
# wall time.  Measured, not inferred from the run's own share: a run
# that got a whole core says nothing of the other core.
hz=$(getconf CLK_TCK)
busy() { awk '/^cpu / { print $2 + $3 + $4 + $7 + $8 + $9; exit }' /proc/stat; }
# others TAG B0 B1 T0 T1: appends the others' cores to $tmp/TAG.x (its
# own CPU time from $tmp/cpu)
others() {
	awk -v b0="$2" -v b1="$3" -v hz="$hz" -v w="$(sub "$5" "$4")" '{
		x = ((b1 - b0) / hz - ($1 + $2)) / w; printf "%.4g ", (x > 0 ? x : 0) }' \
		"$tmp/cpu" >> "$tmp/$1.x"
}

# run TAG CMD...: one trace; appends its trace seconds to $tmp/TAG.s,
# the command's wall time to $tmp/TAG.w, its CPU time (user + sys, all
# its processes) to $tmp/TAG.c and the others' load to $tmp/TAG.x; the
# curve to $tmp/TAG.csv.
run() {
	local tag=$1 t0 t1 b0 b1; shift
	b0=$(busy); t0=$(now)
	/usr/bin/time -o "$tmp/cpu" -f "%U %S" "$@" --out "$tmp/$tag.csv" \
		> "$tmp/j.json" 2> "$tmp/$tag.err"
	t1=$(now); b1=$(busy)
	others "$tag" "$b0" "$b1" "$t0" "$t1"
	awk '{ printf "%s ", $1 + $2 }' "$tmp/cpu" >> "$tmp/$tag.c"
	sed -n 's/.*"seconds":[[:space:]]*\([0-9.e+-]*\).*/\1/p' "$tmp/j.json" \
		| head -n 1 | tr '\n' ' ' >> "$tmp/$tag.s"
	sub "$t1" "$t0" >> "$tmp/$tag.w"; echo -n " " >> "$tmp/$tag.w"
}
vals() { cat "$tmp/$1.${2:-s}"; }
med() { spread $(vals "$@") | cut -d' ' -f1; }
stat() { sed -n "s/.* $2 \([0-9.]*\).*/\1/p" "$tmp/$1.err" | tail -n 1; }

# the detector-side estimator alone: the cost model's pieces and the
# figures of mpi/README.md (B, the default of `trace` since, adds its
# samples to the pieces: tracer/README.md)
args=(trace --scene ref4 --angles "$angles" --rays "$rays" --seed 3 --json
	--no-light-paths)
for ((i = 0; i < pairs; i++)); do
	run t1 "$stray" "${args[@]}" --threads 1
	run n1 mpirun -n 1 "$smpi" --stats "${args[@]}"
	run n2 mpirun -n 2 "$smpi" --stats "${args[@]}"
	run t2 "$stray" "${args[@]}" --threads 2
done
# the same bytes but for the "# command:" and "# version:" lines (a
# binary relinked by a partial make carries a newer git revision)
body() { grep -v -e '^# command:' -e '^# version:' "$1"; }
cmp -s <(body "$tmp/n2.csv") <(body "$tmp/t1.csv") && same=yes || same=NO
worst=$(awk -F, '!/^#/ && $2 + 0 > 0 && $1 + 0 > 0 { r = $3 / $2; if (r > w) w = r }
	END { printf "%.2f", 100 * w }' "$tmp/t1.csv")
echo "ref4, $rays paths, 127 angles (worst sigma/alpha $worst %), seed 3; 2 cores shared"
echo "trace seconds, median (min-max) of $pairs alternating rounds:"
for t in t1 t2 n1 n2; do
	read -r m lo hi < <(spread $(vals $t))
	printf '  %-44s %7.2f s (%.2f-%.2f)\n' "$(case $t in
		t1) echo "stray trace --threads 1 (baseline)";;
		t2) echo "stray trace --threads 2";;
		n1) echo "mpirun -n 1 stray-mpi";;
		n2) echo "mpirun -n 2 stray-mpi";; esac)" "$m" "$lo" "$hi"
done
show "stray-mpi 1 rank / baseline (farm overhead)" "$(vals n1)" "$(vals t1)"
show "speedup 1 -> 2 ranks (t1/t2)" "$(vals n1)" "$(vals n2)"
show "2 ranks vs baseline" "$(vals t1)" "$(vals n2)"
show "2 threads vs baseline (no MPI)" "$(vals t1)" "$(vals t2)"
show "2 ranks vs 2 threads (ranks x threads)" "$(vals t2)" "$(vals n2)"
show "command wall, 2 ranks vs baseline (with start-up)" "$(vals t1 w)" "$(vals n2 w)"
echo "2-rank curve identical to the 1-process curve: $same"
echo "messages (2 ranks): $(stat n2 bytes_per_remote_piece) bytes per main piece," \
	"$(stat n2 pieces) pieces ($(stat n2 remote_pieces) remote), pilot" \
	"$(stat n2 pilot_bytes_per_remote_piece) bytes per piece, job + guide $(stat n2 job_bytes) bytes"

# --- the model's inputs ---------------------------------------------
# 1-rank traces of R and R/4 paths (1 and 4 angle chunks), 12 800 paths,
# and 64 000 paths cut in 1152 pieces (16 chunks of 8 angles): the fit
# below; the last also at 2 ranks, for the latency of a remote piece.
# All alternated.
q=$((rays / 4))
a1=(trace --scene ref4 --angles "$angles" --seed 3 --json --no-light-paths)
for ((i = 0; i < pairs; i++)); do
	run ts1 mpirun -n 1 "$smpi" "${a1[@]}" --rays 12800
	run qk1 mpirun -n 1 "$smpi" "${a1[@]}" --rays "$q"
	run qk4 mpirun -n 1 "$smpi" --angle-chunks 4 "${a1[@]}" --rays "$q"
	run tn1 mpirun -n 1 "$smpi" --stats --angle-chunks 16 "${a1[@]}" --rays 64000
	run tn2 mpirun -n 2 "$smpi" --stats --angle-chunks 16 "${a1[@]}" --rays 64000
done
# --- the 64-design sweep --------------------------------------------
grid=(--grid edge_radius=0,0.005,0.01,0.015,0.02,0.03,0.04,0.05
      --grid reflectance=0.02,0.03,0.04,0.05,0.06,0.07,0.08,0.09)
sweep() {	# sweep TAG N: one 64-design sweep on N ranks, fresh state
	local t0 t1 b0 b1
	rm -rf "$tmp/st"
	b0=$(busy); t0=$(now)
	/usr/bin/time -o "$tmp/cpu" -f "%U %S" \
	mpirun -n "$2" "$smpi" --stats sweep --scene ref4 "${grid[@]}" \
		--rays "$srays" --seed 3 --state "$tmp/st" --out "$tmp/$1.csv" \
		> /dev/null 2> "$tmp/$1.err"
	t1=$(now); b1=$(busy)
	others "$1" "$b0" "$b1" "$t0" "$t1"
	sub "$t1" "$t0" >> "$tmp/$1.w"; echo -n " " >> "$tmp/$1.w"
	awk '{ printf "%s ", $1 + $2 }' "$tmp/cpu" >> "$tmp/$1.c"
	# one set of traces: one stats line; its seconds (no mpirun start-up)
	awk '/stray-mpi: stats/ { s = $NF } END { printf "%.6g ", s }' \
		"$tmp/$1.err" >> "$tmp/$1.s"
	for k in scene_builds rank0_build_s rank0_done_s rank0_start_s remote_pieces \
		pilot_bytes_per_remote_piece bytes_per_remote_piece; do
		echo -n "$(stat "$1" "$k") " >> "$tmp/$1.$k"
	done
}
for ((i = 0; i < pairs; i++)); do sweep s1 1; sweep s2 2; done
# The 1-rank runs fit T = Ts + c0 A + alpha X + beta Y (least squares,
# 5 runs, 4 unknowns): A pieces, X path tracings (every angle chunk
# retraces its paths), Y paths connected to all the angles; the pilot
# is min(R / 10, 200000) paths in 8 batches when R / 10 >= 1000.  c0 is
# a piece's fixed cost (tracer_trace_batches sets up a pass: ~1 ms).
T0=$(med ts1)
read -r Ts c0 alpha beta < <(awk -v r="$rays" -v q="$q" \
	-v t="$(med n1) $T0 $(med qk1) $(med qk4) $(med tn1)" '
	function row(i, R, K, y) { p = R / 10 >= 1000 ? (R / 10 > 200000 ? 200000 : R / 10) : 0;
		a[i, 1] = 1; a[i, 2] = (64 + (p ? 8 : 0)) * K; a[i, 3] = K * (R + p);
		a[i, 4] = R + p; rhs[i] = y }
	# least squares of the relative errors (rows weighted by 1 / T^2)
	# over the unknowns still free; a negative one is held at 0 and the
	# others fitted again (non-negative least squares, 4 unknowns)
	function solve(    i, j, k, s, f, m, u, v) {
		m = 0; for (i = 1; i <= 4; i++) if (free[i]) idx[++m] = i;
		for (u = 1; u <= m; u++) { for (v = 1; v <= m; v++) { s = 0;
			for (k = 1; k <= 5; k++) s += a[k, idx[u]] * a[k, idx[v]] / rhs[k] ^ 2;
			n[u, v] = s }
			s = 0; for (k = 1; k <= 5; k++) s += a[k, idx[u]] * rhs[k] / rhs[k] ^ 2;
			n[u, m + 1] = s }
		for (i = 1; i <= m; i++) for (k = i + 1; k <= m; k++) { f = n[k, i] / n[i, i];
			for (j = i; j <= m + 1; j++) n[k, j] -= f * n[i, j] }
		for (i = 1; i <= 4; i++) x[i] = 0;
		for (i = m; i >= 1; i--) { s = n[i, m + 1];
			for (j = i + 1; j <= m; j++) s -= n[i, j] * x[idx[j]];
			x[idx[i]] = s / n[i, i] }
	}
	BEGIN { split(t, T, " ");
	row(1, r, 1, T[1]); row(2, 12800, 1, T[2]); row(3, q, 1, T[3]);
	row(4, q, 4, T[4]); row(5, 64000, 16, T[5]);
	for (i = 1; i <= 4; i++) free[i] = 1;
	for (it = 0; it < 4; it++) { solve(); worst = 0;
		for (i = 1; i <= 4; i++) if (free[i] && x[i] < 0 && (!worst || x[i] < x[worst])) worst = i;
		if (!worst) break; free[worst] = 0 }
	for (i = 1; i <= 4; i++) if (x[i] < 0) x[i] = 0;
	printf "%.6g %.6g %.6g %.6g\n", x[1], x[2], x[3], x[4] }')
# rank 1 did pr of the many-piece trace's 1024 main pieces (64000 paths,
# 64 batches x 16 chunks, and 128 pilot pieces) in about (T2 - Ts - b):
# per piece that, less a piece's own cost on rank 0 (T1 - Ts) / 1152:
# the latency of a remote piece (rank 0's 1 ms polling naps, its tracing
# thread on the same core, the messages).
bw=${BENCH_MPI_BW:-1e9}
Tt1=$(med tn1); Tt2=$(med tn2); pr=$(stat tn2 remote_pieces)
sb0=$(awk -v n="$(med s1 scene_builds)" -v t="$(med s1 rank0_build_s)" \
	'BEGIN { printf "%.6g", t / (n > 0 ? n : 1) }')
mm=$(awk -v t1="$Tt1" -v t2="$Tt2" -v s="$Ts" -v pr="$pr" -v b="$sb0" 'BEGIN {
	pr *= 1152 / 1024;	# its pilot pieces (8 x 16) in the same share
	x = (t2 - s - b) / (pr > 0 ? pr : 1) - (t1 - s) / 1152;
	printf "%.6g", (x > 0 ? x : 0) }')
# mpirun and MPI_Init: the 1- and 2-rank commands' wall beyond the trace
up1=$(sub "$(med n1 w)" "$(med n1)"); up2=$(sub "$(med n2 w)" "$(med n2)")
# the sweep at 1 rank: a scene build b, the caller's work per design Tc
# (curve written, read back, judged), rank 0's start S (every design's
# scene checked, the options once), all from its --stats line
sb=$(awk -v n="$(med s1 scene_builds)" -v t="$(med s1 rank0_build_s)" \
	'BEGIN { printf "%.6g", t / (n > 0 ? n : 1) }')
sTc=$(awk -v t="$(med s1 rank0_done_s)" 'BEGIN { printf "%.6g", t / 64 }')
sS=$(awk -v a="$(med s1 rank0_start_s)" -v s="$Ts" 'BEGIN { printf "%.6g", a + s }')
# bytes per piece (one chunk, all angles), from the 2-rank runs
bm=$(stat n2 bytes_per_remote_piece); bp=$(stat n2 pilot_bytes_per_remote_piece)
sbm=$(med s2 bytes_per_remote_piece); sbp=$(med s2 pilot_bytes_per_remote_piece)
echo "model inputs (medians; bench/mpi_model.awk, mpi/README.md):"
printf '  fixed farm cost per trace Ts %.3f s (12800-path trace: %.3f s)\n' "$Ts" "$T0"
printf '  per piece c0 %.3g s; per path: tracing alpha %.3g s (repeated per angle chunk), connections to 127 angles beta %.3g s\n' "$c0" "$alpha" "$beta"
printf '  latency of a remote piece m %.3g s (1152-piece trace: 1 rank %.3f s, 2 ranks %.3f s, %d main pieces remote)\n' "$mm" "$Tt1" "$Tt2" "$pr"
printf '  bytes per piece: curve main %s, pilot %s; sweep main %s, pilot %s; rank 0 receives at %.3g bytes/s (assumed)\n' "$bm" "$bp" "$sbm" "$sbp" "$bw"
printf '  sweep, per design: scene build b %.4f s, curve kept Tc %.4f s; rank 0 start S %.3f s; command start-up %.2f s (1 rank), %.2f s (2)\n' "$sb" "$sTc" "$sS" "$up1" "$up2"

model() { awk -f bench/mpi_model.awk -v S="$Ts" -v c0="$c0" -v alpha="$alpha" \
	-v beta="$beta" -v m="$mm" -v b=0 -v Tc=0 -v bm="$bm" -v bp="$bp" \
	-v bw="$bw" -v B=64 -v D=1 -v angles=127 -v R="$rays" "$@"; }
pred2=$(model -v ranks=2 | awk 'NR == 2 { print $2 }')
pt1=$(model -v ranks=1 | awk 'NR == 2 { print $2 }')
meas2=$(med n2)
echo "check, trace at 2 ranks on 2 free cores: model $(printf %.2f "$pred2") s, measured $(printf %.2f "$meas2") s" \
	"(median), error $(awk -v p="$pred2" -v m="$meas2" 'BEGIN { printf "%+.1f", 100 * (p / m - 1) }') %"
# The machine is shared: with X1 cores' worth of others' threads
# runnable (measured, above) the 1-rank run got share1 = min(1, 2 /
# (1 + X1)) of a core, and with X2 each of the two ranks got share2 =
# min(1, 2 / (2 + X2)).  Per pair: predicted T2 = T1 (model T2 / model
# T1) share1 / share2; on a quiet machine (X = 0) the raw prediction.
loaded() {	# loaded T1S T1X T2S T2X G: per pair "pred:meas:X1:X2"
	awk -v t1="$1" -v x1="$2" -v t2="$3" -v x2="$4" -v g="$5" 'BEGIN {
	n = split(t1, a, " "); split(x1, p, " "); split(t2, b, " ");
	split(x2, q, " ");
	for (i = 1; i <= n; i++) {
		s1 = 2 / (1 + p[i]); if (s1 > 1) s1 = 1;
		s2 = 2 / (2 + q[i]); if (s2 > 1) s2 = 1;
		printf "%.4g:%.4g:%.3g:%.3g ", a[i] * g * s1 / s2, b[i], p[i], q[i]
	} }'
}
check_loaded() {	# check_loaded LABEL T1S T1X T2S T2X G
	local pl="" ml="" xl="" v p2 m2 x1 x2 xm xlo xhi label=$1; shift
	for v in $(loaded "$@"); do
		IFS=: read -r p2 m2 x1 x2 <<< "$v"; pl+="$p2 "; ml+="$m2 "
		xl+="$x1 $x2 "
	done
	read -r xm xlo xhi < <(spread $xl)
	printf '%s under the load measured in each run (others: %.2f cores busy, %.2f-%.2f):\n' "$label" "$xm" "$xlo" "$xhi"
	show "  model / measured (target within 10 %)" "$pl" "$ml"
}
check_loaded "check, trace at 2 ranks" "$(vals n1)" "$(vals n1 x)" \
	"$(vals n2)" "$(vals n2 x)" "$(div "$pred2" "$pt1")"
echo "model, 127-angle curve at $rays paths (efficiency against the model's 1 rank):"
model -v ranks="1 2 16 64 256"

cmp -s <(body "$tmp/s1.csv") <(body "$tmp/s2.csv") && same=yes || same=NO
echo "sweep, 64 designs x $srays paths, default angles (67), seed 3, the designs farmed together:"
printf '  1 rank: command %.1f s, set %.1f s; 2 ranks: command %.1f s, set %.1f s (medians)\n' \
	"$(med s1 w)" "$(med s1)" "$(med s2 w)" "$(med s2)"
show "  sweep speedup 1 -> 2 ranks, command" "$(vals s1 w)" "$(vals s2 w)"
show "  sweep speedup 1 -> 2 ranks, set (no start-up)" "$(vals s1)" "$(vals s2)"
echo "  2-rank table identical to the 1-rank table: $same;" \
	"scenes built: $(med s1 scene_builds) (1 rank), $(med s2 scene_builds) (2 ranks)"
# the sweep's traces at 67 angles: connections scale with the angles;
# alpha and beta then scaled to the sweep's own 1-rank time per design
read -r salpha sbeta < <(awk -v a="$alpha" -v b="$beta" -v t="$(med s1)" \
	-v s="$sS" -v bb="$sb" -v tc="$sTc" -v r="$srays" -v c0="$c0" 'BEGIN { b *= 67 / 127;
	f = ((t - s) / 64 - bb - tc - 72 * c0) / (1.1 * r * (a + b)); if (f <= 0) f = 1;
	printf "%.6g %.6g\n", a * f, b * f }')
smodel() { awk -f bench/mpi_model.awk -v S="$sS" -v c0="$c0" -v alpha="$salpha" \
	-v beta="$sbeta" -v m="$mm" -v b="$sb" -v Tc="$sTc" -v bm="$sbm" \
	-v bp="$sbp" -v bw="$bw" -v B=64 -v D=64 -v angles=67 "$@"; }
pred2=$(smodel -v R="$srays" -v ranks=2 | awk 'NR == 2 { print $2 }')
pt1=$(smodel -v R="$srays" -v ranks=1 | awk 'NR == 2 { print $2 }')
meas2=$(med s2)
printf '  per path (67 angles, scaled to this sweep): alpha %.3g s, beta %.3g s\n' "$salpha" "$sbeta"
echo "check, sweep at 2 ranks on 2 free cores: model $(printf %.2f "$pred2") s, measured $(printf %.2f "$meas2") s" \
	"(set, median), error $(awk -v p="$pred2" -v m="$meas2" 'BEGIN { printf "%+.1f", 100 * (p / m - 1) }') %"
check_loaded "check, sweep at 2 ranks" "$(vals s1)" "$(vals s1 x)" \
	"$(vals s2)" "$(vals s2 x)" "$(div "$pred2" "$pt1")"
for r in 1500000 300000 "$srays"; do
	echo "model, 64-design sweep at $r paths per design:"
	smodel -v R="$r" -v ranks="1 2 16 64 256"
done
