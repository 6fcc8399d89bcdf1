#!/bin/sh
# validate-cedar.sh BUILD PYTHON [OUT] - the tetra3 detector model against
# cedar-solve's own extractor (tetra3.get_centroids_from_image, defaults
# but sigma; cedar-solve==0.5.1, a test-only dependency: PYTHON is an
# interpreter that has it, e.g. a venv's).  Frames: 256 x 256 px, uniform
# stray light, one designed reference star at a random place
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
echo "| sigma | alpha | frames | P(DRS) cedar | P model | model - cedar | false stars per frame (cedar) | model |"
echo "|---|---|---|---|---|---|---|---|"
for point in 3:3e-8 3:5e-8 3:7e-8 3:1e-7 3:1.5e-7 5:2e-8 5:3e-8 5:5e-8 5:7e-8; do
	k=${point%%:*}
	a=${point#*:}
	"$build/tests/frames/render_drs" "$a" "$frames" 28 "$out/f_$a.bin"
	model=$("$build/bin/stray" fdr --detector tetra3 --detector-sigma "$k" \
		--alpha "$a" --json)
	"$py" - "$out/f_$a.bin" "$k" "$a" "$frames" "$model" <<'PY'
import json, sys, warnings
import numpy as np
warnings.filterwarnings("ignore")
from tetra3 import get_centroids_from_image
path, k, a, n, model = sys.argv[1], float(sys.argv[2]), sys.argv[3], int(sys.argv[4]), json.loads(sys.argv[5])
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
print("| %g | %s | %d | %.3f ± %.3f | %.3f | %+.3f | %.3g | %.2g |" % (
    k, a, len(data), p, (p * (1 - p) / len(data)) ** 0.5,
    model["drs_detection_probability"],
    model["drs_detection_probability"] - p, false / len(data), fs))
PY
	rm -f "$out/f_$a.bin"
done
