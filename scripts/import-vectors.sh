#!/bin/sh
# import-vectors.sh BUILD [check] - the test vectors of `stray sweep import`
# (tests/vectors/import/README.md), written by other software: astropy and
# tifffile, pinned, in a venv (BUILD/venv-import; needs PyPI once).
#   import-vectors.sh build         rewrite tests/vectors/import/{native,foreign}
#                                   from a new simulated sweep (rig.json there)
#   import-vectors.sh build check   the import's own end-to-end check on a fresh
#                                   sweep of the e2e rig (7 angles, rows
#                                   960,961,1100,1101): FITS and TIFF imported,
#                                   reduced, every alpha and sigma equal to the
#                                   native folder's to the last bit
set -eu
build=${1:-build}
mode=${2:-vectors}
venv=$build/venv-import
py=$venv/bin/python
pins="astropy==7.1.1 numpy==2.2.6 tifffile==2025.6.11"
if ! "$py" -c 'import astropy, tifffile' 2>/dev/null; then
	python3 -m venv "$venv"
	"$venv/bin/pip" install -q $pins
fi
vec=tests/vectors/import
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ "$mode" = check ]; then
	printf '%s' '{"camera":{"rows":[960,961,1100,1101],"col0":800,"n_cols":256},"sweep":{"theta_stop_deg":30,"theta_step_deg":5,"repeats":3}}' >"$tmp/rig.json"
else
	cp "$vec/rig.json" "$tmp/rig.json"
fi
"$build/bin/strayrigd" --config "$tmp/rig.json" --sweep "$tmp/native" 2>/dev/null
"$py" "$vec/make_foreign.py" "$tmp/native" "$tmp/foreign"
if [ "$mode" = check ]; then
	s=$build/bin/stray
	"$s" --json reduce "$tmp/native" --out "$tmp/native.csv" >"$tmp/native.json"
	for k in fits tiff; do
		"$s" sweep import --log "$tmp/foreign/log_$k.csv" --out "$tmp/imp_$k" \
			--col0 800 --row0 960 --satlevel 4095 "$tmp/foreign/$k" >/dev/null
		"$s" --json reduce "$tmp/imp_$k" --out "$tmp/$k.csv" >"$tmp/$k.json"
		python3 - "$tmp/native.json" "$tmp/$k.json" "$k" <<'PY'
import json, sys
a, b = (json.load(open(p))["curve"] for p in sys.argv[1:3])
assert len(a) == len(b) and len(a) > 1, "curves differ in length"
for x, y in zip(a, b):
    print("%s theta %5.1f  alpha native %.17g imported %.17g  %s" % (
        sys.argv[3], x["theta_deg"], x["alpha"], y["alpha"],
        "equal" if x == y else "DIFFERENT"))
    assert x == y
PY
	done
	exit 0
fi
rm -rf "$vec/native" "$vec/foreign"
mkdir "$vec/native"
cp "$tmp/native/manifest.csv" "$tmp/native"/a*.fits "$vec/native/"
cp -r "$tmp/foreign" "$vec/foreign"
"$venv/bin/pip" freeze | grep -iE '^(astropy|numpy|tifffile|pyerfa)==' >"$vec/foreign/WRITTEN_BY"
python3 --version >>"$vec/foreign/WRITTEN_BY"
