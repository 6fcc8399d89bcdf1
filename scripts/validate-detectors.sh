#!/bin/sh
# validate-detectors.sh BUILD [OUT] - lost stars on rendered full frames:
# the fraction of true stars the OpenCV detectors of `stray frames` find
# per 0.1 mag, against the lost-star model of stray/detector.h as each
# frame sets the detectors (model) and the sensor's (model_nominal) (issue
# 28, docs/detectors.md).  FRAMES frames per alpha (default 60: ~200 stars
# per bin near m 6); a few minutes.
set -eu
build=${1:-build}
out=${2:-$build/validate-detectors}
frames=${FRAMES:-60}
mkdir -p "$out"
for a in 0 1e-7 2e-7 3e-7; do
	"$build/bin/stray" frames --alpha "$a" --frames "$frames" --seed 28 \
		--json > "$out/frames_$a.json"
done
python3 - "$out" <<'PY'
import json, sys, glob
out = sys.argv[1]
print("| alpha | detector | mag | stars | found | model | model - found | nominal | nominal - found |")
print("|---|---|---|---|---|---|---|---|---|")
for f in sorted(glob.glob(out + "/frames_*.json")):
    o = json.load(open(f))
    for det, rows in o["lost_stars"].items():
        for r in rows:
            if r["stars"] >= 50 and 0.05 <= r["found"] <= 0.95:
                print("| %g | %s | %.1f-%.1f | %d | %.3f ± %.3f | %.3f | %+.3f | %.3f | %+.3f |" % (
                    o["alpha"], det, r["mag_lo"], r["mag_hi"], r["stars"],
                    r["found"], r["sigma"], r["model"], r["model"] - r["found"],
                    r["model_nominal"], r["model_nominal"] - r["found"]))
PY
