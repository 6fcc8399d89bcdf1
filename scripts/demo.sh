#!/usr/bin/env bash
# make demo: the whole method on the built-in reference system (st16-like
# sensor, ref4 baffle), every output in one folder with an HTML report.
#   simulated lab sweep of the lens (strayrigd, simulators) -> reduction ->
#   trace of ref4 with that lens -> FDR and exclusion angles -> a design
#   variant -> flight table -> the flight module along a day in orbit
# Usage: scripts/demo.sh BUILD_DIR [OUT_DIR]
set -euo pipefail
build=${1:-build}
out=${2:-$build/demo}
stray="$build/bin/stray"
rigd="$build/bin/strayrigd"
rays=${DEMO_RAYS:-1500000}
rm -rf "$out"
mkdir -p "$out"
step=0; steps=10
say() { step=$((step + 1)); printf '\n[%d/%d] %s\n' "$step" "$steps" "$*"; }
start=$(date +%s)

say "photometry: reference fluxes of st16-like (thesis table 2.1)"
"$stray" photometry | tee "$out/photometry.txt"
"$stray" photometry --json > "$out/photometry.json"

say "fdr: attenuation required for 5 false stars per image (fig. 2.7)"
"$stray" fdr --plot "$out/fdr_sun.png"
"$stray" fdr --json > "$out/fdr_sun.json"

say "rig: simulated lab sweep of the st16-like lens, 0-45 deg, faults injected"
"$rigd" --config examples/rig-demo.json --sweep "$out/sweep" 2>&1 |
	grep -v "frames, theta" | tee "$out/rig.txt"

say "reduce: the lens attenuation curve, its noise floor and its ghosts"
"$stray" reduce "$out/sweep" --out "$out/lens.csv" --plot-dir "$out" \
	--map "$out/lens_map.csv" --json > "$out/reduce.json"
"$stray" reduce "$out/sweep" --out "$out/lens.csv" | tail -n 12

say "trace: ref4 with the measured lens ($rays paths)"
"$stray" trace --scene ref4 --lens "$out/lens.csv" --rays "$rays" \
	--out "$out/system.csv" --plot-orders "$out/orders.png" \
	--json > "$out/trace.json"
"$stray" trace --scene ref4 --lens "$out/lens.csv" --rays 200000 \
	--angles 30,45,60,75,85 --top 3 --out "$out/top_paths.csv" \
	> "$out/paths.txt" 2>/dev/null
cat "$out/trace.json" "$out/paths.txt"

say "exclusion: Sun, Moon and Earth-limb angles of the system (fig. 5.1)"
"$stray" exclusion --curve "$out/system.csv" --earth-albedo 0.3 \
	--plot "$out/exclusion.png" 2>&1 | tee "$out/exclusion.txt"
"$stray" exclusion --curve "$out/system.csv" --earth-albedo 0.3 \
	--json > "$out/exclusion.json" 2>/dev/null

say "design variant: the path analysis blames the vane bevels; flip them"
"$stray" trace --scene ref4 --set bevel_face=upper --lens "$out/lens.csv" \
	--rays "$rays" --out "$out/system_variant.csv" > /dev/null
{ echo; echo "Variant: bevels on the upper faces (--set bevel_face=upper)"; } |
	tee -a "$out/exclusion.txt"
"$stray" exclusion --curve "$out/system_variant.csv" --earth-albedo 0.3 \
	--plot "$out/exclusion_variant.png" 2>&1 | tee -a "$out/exclusion.txt"

say "firmware: flight table of the variant and the module's footprint"
"$stray" firmware-table --curve "$out/system_variant.csv" \
	--out-c "$out/flight_table.c" --out-bin "$out/flight_table.bin" \
	--json > "$out/firmware.json"
env -u MAKEFLAGS -u MFLAGS make --no-print-directory -s firmware B="$build" \
	2>&1 | grep -v '^arm-none-eabi-gcc' > "$out/firmware.txt" || true
cat "$out/firmware.json" "$out/firmware.txt"

say "orbit: the flight module along a day of a 550 km sun-synchronous orbit"
"$stray" orbit --table "$out/flight_table.bin" --plot "$out/orbit" \
	--out "$out/orbit.csv" | tee "$out/orbit.txt"
"$stray" orbit --table "$out/flight_table.bin" --json > "$out/orbit.json"

say "report: $out/report.html (and report.md)"
"$stray" report "$out"
if command -v chromium >/dev/null; then
	scripts/check-report.sh "$out"
fi
echo "demo: done in $(( $(date +%s) - start )) s; open $out/report.html"
