#!/bin/sh
# validate-cedar.sh BUILD PYTHON [OUT] - the tetra3 detector model against
# cedar-solve's own extractor (tetra3.get_centroids_from_image, defaults
# but sigma; cedar-solve==0.5.1, a test-only dependency: PYTHON is an
# interpreter that has it, e.g. a venv's).  Frames: 256 x 256 px, uniform
# and mapped stray light (LIGHTS, default both; mapped: a ramp 0.7-1.3
# times a 0.5 % ripple of 256 px, the model told its 64 levels through
# `stray fdr --map`), one designed reference star at a random place
# (tests/frames/render_drs.c); FRAMES per point (400).  Prints the
# detection probability measured and modelled and the false stars.
set -eu
build=${1:-build}
py=${2:-python3}
out=${3:-$build/validate-cedar}
frames=${FRAMES:-400}
make -s "$build/tests/frames/render_drs" B="$build" >/dev/null
mkdir -p "$out"
"$py" -c 'import tetra3' 2>/dev/null || {
	echo "validate-cedar: $py has no tetra3 (pip install cedar-solve==0.5.1)" >&2
	exit 2
}
echo "| light | sigma | alpha | frames | P(DRS) cedar | P model | model - cedar | pass (0.05) | false stars per frame (cedar) | model |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for light in ${LIGHTS:-uniform mapped}; do
for point in 3:3e-8 3:5e-8 3:7e-8 3:1e-7 3:1.5e-7 5:2e-8 5:3e-8 5:5e-8 5:7e-8; do
	k=${point%%:*}
	a=${point#*:}
	if [ "$light" = mapped ]; then
		"$build/tests/frames/render_drs" "$a" "$frames" 28 "$out/f_$a.bin" mapped
		set -- --map "$out/f_$a.bin.regions.csv"
	else
		"$build/tests/frames/render_drs" "$a" "$frames" 28 "$out/f_$a.bin"
		set --
	fi
	model=$("$build/bin/stray" fdr --detector tetra3 --detector-sigma "$k" \
		--alpha "$a" "$@" --json)
	"$py" - "$out/f_$a.bin" "$k" "$a" "$frames" "$model" "$light" <<'PY'
import json, sys, warnings
import numpy as np
warnings.filterwarnings("ignore")
from tetra3 import get_centroids_from_image
path, k, a, n, model, light = sys.argv[1], float(sys.argv[2]), sys.argv[3], int(sys.argv[4]), json.loads(sys.argv[5]), sys.argv[6]
W = 256
rec = np.dtype([("xy", "<f4", 2), ("dn", "<u2", (W, W))])
data = np.fromfile(path, dtype=rec)
found = false = 0
for f in data:
    c = get_centroids_from_image(f["dn"], sigma=k)
    x, y = f["xy"]
    hit = 0
    for cy, cx in (c if len(c) else []):
        # cedar's pixel centres are integers, the renderer's integer + 0.5
        if (cx + 0.5 - x) ** 2 + (cy + 0.5 - y) ** 2 <= 9.0:
            hit = 1
        else:
            false += 1
    found += hit
p = found / len(data)
# the model's false stars are per full st16-like image: per 256^2 frame
fs = model["false_stars_per_image"] * W * W / (2592 * 1944)
pm = model["drs_detection_probability"]
verdict = ("pass" if abs(pm - p) <= 0.05 else "FAIL") if 0.05 <= p <= 0.95 else "(outside 0.05-0.95)"
print("| %s | %g | %s | %d | %.3f ± %.3f | %.3f | %+.3f | %s | %.3g | %.2g |" % (
    light, k, a, len(data), p, (p * (1 - p) / len(data)) ** 0.5,
    pm, pm - p, verdict, false / len(data), fs))
PY
	rm -f "$out/f_$a.bin" "$out/f_$a.bin.regions.csv"
done
done
