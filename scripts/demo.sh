#!/usr/bin/env bash
# make demo: the main job on the built-in reference system (st16-like
# sensor, ref4 baffle), every output in one folder with a Markdown report.
# Usage: scripts/demo.sh BUILD_DIR [OUT_DIR]
set -euo pipefail
build=${1:-build}
out=${2:-$build/demo}
stray="$build/bin/stray"
mkdir -p "$out"
step=0; steps=3
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

cat > "$out/report.md" <<MD
# straylight demo: st16-like sensor, ref4 baffle

## Reference fluxes (thesis table 2.1)
\`\`\`
$(cat "$out/photometry.txt")
\`\`\`

## False-detection rate (thesis §2.3, fig. 2.7)
\`\`\`
$(cat "$out/fdr_sun.txt")
\`\`\`
![FDR vs alpha](fdr_sun.png)

## Exclusion angles (thesis §5.1, fig. 5.1)
Curve: \`$curve\` (the ref4 baffle alone, traced by the Mitsuba 3 peer; the
lens attenuation that makes the system curve comes from \`stray reduce\`).
\`\`\`
$(cat "$out/exclusion.txt")
\`\`\`
![exclusion](exclusion.png)
MD
echo "demo: done in $(( $(date +%s) - start )) s; report: $out/report.md"
