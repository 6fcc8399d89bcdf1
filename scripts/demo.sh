#!/usr/bin/env bash
# make demo: the main job on the built-in reference system (st16-like
# sensor, ref4 baffle), every output in one folder with a Markdown report.
# Usage: scripts/demo.sh BUILD_DIR [OUT_DIR]
set -euo pipefail
build=${1:-build}
out=${2:-$build/demo}
stray="$build/bin/stray"
mkdir -p "$out"
step=0; steps=4
say() { step=$((step + 1)); printf '[%d/%d] %s\n' "$step" "$steps" "$*"; }
start=$(date +%s)

say "photometry: reference fluxes of st16-like (thesis table 2.1)"
"$stray" photometry | tee "$out/photometry.txt"
"$stray" photometry --json > "$out/photometry.json"

say "fdr: attenuation required for 5 false stars per image (fig. 2.7)"
"$stray" fdr --plot "$out/fdr_sun.png" | tee "$out/fdr_sun.txt"
"$stray" fdr --json > "$out/fdr_sun.json"
"$stray" fdr --source moon --json > "$out/fdr_moon.json"

curve=examples/ref4_baffle_mitsuba.csv
say "exclusion: Sun and Moon angles of $curve (fig. 5.1)"
"$stray" exclusion --curve "$curve" --earth-albedo 0.3 \
	--plot "$out/exclusion.png" 2>&1 | tee "$out/exclusion.txt"
"$stray" exclusion --curve "$curve" --earth-albedo 0.3 --json \
	> "$out/exclusion.json" 2>/dev/null

say "report: $out/report.html (and report.md)"
"$stray" report "$out"
if command -v chromium >/dev/null; then
	scripts/check-report.sh "$out"
fi
echo "demo: done in $(( $(date +%s) - start )) s; report: $out/report.md"
