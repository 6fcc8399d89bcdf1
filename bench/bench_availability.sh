#!/usr/bin/env bash
# bench_availability.sh - `stray availability` over one year at 10 s steps
# (3.15 M epochs) for three heads, the orbit and attitude from OEM/AEM
# files of the demo mission written every 60 s.  Baseline in the same run:
# `stray orbit`, the flight module alone along its idealised orbit (one
# head, no files, no interpolation, no albedo), 30 days at 10 s.  Prints
# epochs/s per head and its ratio to the baseline's frames/s; the issue's
# target is the year in <= 30 s on 2 cores.
set -eu
stray=${STRAY_BIN:-build/bin/stray}
days=${BENCH_AVAIL_DAYS:-365}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
"$stray" firmware-table --curve tests/vectors/fdrfw_curve.csv \
	--out-bin "$tmp/t.bin" > /dev/null
cat > "$tmp/heads.json" <<'JSON'
{"heads": [
 {"name": "A", "boresight_body": [0, 0.6428, -0.7660], "table": "t.bin"},
 {"name": "B", "boresight_body": [0, -0.6428, -0.7660], "table": "t.bin"},
 {"name": "C", "boresight_body": [-0.6428, 0, -0.7660], "table": "t.bin"}
]}
JSON
t0=$(now)
"$stray" orbit --table "$tmp/t.bin" --hours 720 --step-s 10 > /dev/null
t1=$(now)
"$stray" availability --write-oem "$tmp/y.oem" --write-aem "$tmp/y.aem" \
	--hours $((days * 24)) --gen-step-s 60 > /dev/null
t2=$(now)
# CPU time too (user + sys, both cores): steadier than wall time on a
# shared machine.
timer=()
[ -x /usr/bin/time ] && timer=(/usr/bin/time -o "$tmp/cpu" -f "%U %S")
${timer[@]+"${timer[@]}"} "$stray" availability --oem "$tmp/y.oem" --aem "$tmp/y.aem" \
	--heads "$tmp/heads.json" --step-s 10 --json > "$tmp/y.json"
t3=$(now)
cpu=$(awk '{print $1 + $2}' "$tmp/cpu" 2>/dev/null || echo "?")
epochs=$(sed -n 's/.*"epochs":[[:space:]]*\([0-9]*\).*/\1/p' "$tmp/y.json")
awk -v b0="$t0" -v b1="$t1" -v w="$(echo "$t2 - $t1" | bc)" -v a0="$t2" \
	-v a1="$t3" -v n="$epochs" -v days="$days" -v cpu="$cpu" 'BEGIN {
	base = 259201 / (b1 - b0); t = a1 - a0; rate = n / t;
	printf "baseline: stray orbit, 1 head, 259201 frames: %.0f frames/s\n", base;
	printf "writing the %d-day OEM/AEM (60 s): %.1f s\n", days, w;
	printf "availability: %d epochs x 3 heads in %.1f s: %.0f epochs/s per head (%.2f x baseline)\n", n, t, rate, rate / base;
	printf "availability CPU time (user + sys): %s s\n", cpu;
	printf "target one year <= 30 s: %s\n", (days == 365 ? (t <= 30 ? "met" : "NOT met") : "n/a (BENCH_AVAIL_DAYS)");
}'
