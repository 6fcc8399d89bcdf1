#!/usr/bin/env bash
# bench_availability.sh - `stray availability` over one year at 10 s steps
# (3.15 M epochs) for three heads, the orbit and attitude from OEM/AEM
# files of the demo mission written every 60 s.  Baseline: `stray orbit`,
# the flight module alone along its idealised orbit (one head, no files,
# no interpolation, no albedo), 30 days at 10 s, run right before each
# availability run (alternating, BENCH_PAIRS pairs, default 3: bench/
# alt.sh).  Prints epochs/s per head, its ratio to the baseline's
# frames/s as the median and min-max of the pairs, and the wall time
# against the issue's target (the year in <= 30 s on 2 cores).
set -eu
. bench/alt.sh
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
t1=$(now)
"$stray" availability --write-oem "$tmp/y.oem" --write-aem "$tmp/y.aem" \
	--hours $((days * 24)) --gen-step-s 60 > /dev/null
t2=$(now)
# CPU time too (user + sys, both cores): steadier than wall time on a
# shared machine.
timer=()
[ -x /usr/bin/time ] && timer=(/usr/bin/time -o "$tmp/cpu" -f "%U %S")
base="" rate="" wall="" cpu=""
for ((i = 0; i < pairs; i++)); do
	b0=$(now)
	"$stray" orbit --table "$tmp/t.bin" --hours 720 --step-s 10 > /dev/null
	b1=$(now)
	${timer[@]+"${timer[@]}"} "$stray" availability --oem "$tmp/y.oem" \
		--aem "$tmp/y.aem" --heads "$tmp/heads.json" --step-s 10 \
		--json > "$tmp/y.json"
	a1=$(now)
	epochs=$(sed -n 's/.*"epochs":[[:space:]]*\([0-9]*\).*/\1/p' "$tmp/y.json")
	base+="$(awk -v a="$b0" -v b="$b1" 'BEGIN { print 259201 / (b - a) }') "
	rate+="$(awk -v a="$b1" -v b="$a1" -v n="$epochs" 'BEGIN { print n / (b - a) }') "
	wall+="$(awk -v a="$b1" -v b="$a1" 'BEGIN { print b - a }') "
	cpu+="$(awk '{print $1 + $2}' "$tmp/cpu" 2>/dev/null || echo 0) "
done
read -r bm blo bhi < <(spread $base)
read -r rm rlo rhi < <(spread $rate)
read -r wm wlo whi < <(spread $wall)
read -r cm clo chi < <(spread $cpu)
echo "median (min-max) of $pairs alternating pairs (stray orbit, stray availability):"
printf 'baseline: stray orbit, 1 head, 259201 frames: %.0f frames/s (%.0f-%.0f)\n' "$bm" "$blo" "$bhi"
printf 'writing the %d-day OEM/AEM (60 s): %.1f s\n' "$days" "$(awk -v a="$t1" -v b="$t2" 'BEGIN { print b - a }')"
printf 'availability: %d epochs x 3 heads in %.1f s (%.1f-%.1f): %.0f epochs/s per head\n' \
	"$epochs" "$wm" "$wlo" "$whi" "$rm"
show "availability epochs/s per head / baseline frames/s" "$rate" "$base"
printf 'availability CPU time (user + sys): %.1f s (%.1f-%.1f)\n' "$cm" "$clo" "$chi"
if [ "$days" = 365 ]; then
	awk -v t="$wm" 'BEGIN { printf "target one year <= 30 s: %s (median)\n", (t <= 30 ? "met" : "NOT met") }'
else
	echo "target one year <= 30 s: n/a (BENCH_AVAIL_DAYS)"
fi
