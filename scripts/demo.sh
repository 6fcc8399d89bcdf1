#!/usr/bin/env bash
# make demo: the whole method on the built-in reference system (st16-like
# sensor, ref4 baffle), every output in one folder with an HTML report.
#   simulated lab sweep of the lens (strayrigd, simulators) -> reduction ->
#   trace of ref4 with that lens -> a virtual photometer sweep of the baffle
#   alone, with effects the model does not know -> diagnosis -> corrected
#   system, FDR and exclusion angles -> a design variant -> what the thesis
#   model gets wrong about pixels (k_px, mapped stray light, rendered
#   frames) -> flight table -> the flight module along a day in orbit ->
#   availability -> the tracker seen from its own flight frames -> the
#   same system and two user projects reviewed from project files
#   (stray review) -> report
# Usage: scripts/demo.sh BUILD_DIR [OUT_DIR]
# DEMO_RAYS (paths per curve) and DEMO_STEP_DEG (photometer step) scale it;
# DEMO_FRAMES=PX renders PX x PX windows instead of full frames (not the
# flight frames of flightcheck: full always, below).
set -euo pipefail
build=${1:-build}
out=${2:-$build/demo}
stray="$build/bin/stray"
rigd="$build/bin/strayrigd"
rays=${DEMO_RAYS:-1500000}
step_deg=${DEMO_STEP_DEG:-1}
rm -rf "$out"
mkdir -p "$out"
step=0; steps=17
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

# What the designer did not know: the anodise reflects 8 %, not the 4 % of
# the literature, and the knife edges are ground to 0.05 mm (thesis §4).
say "photometer: a lab sweep of the baffle alone, 0-85 deg every $step_deg deg (thesis §4.1)"
"$stray" trace --scene ref4 --set reflectance=0.08 --set edge_radius=0.05 \
	--angles "0:85:$step_deg" --rays "$rays" --seed 4242 \
	--out "$out/baffle_truth.csv" > /dev/null
"$stray" photometer --truth "$out/baffle_truth.csv" \
	--out "$out/baffle_measured.csv" --seed 7
echo "measured curve: $out/baffle_measured.csv ($(grep -vc '^#' "$out/baffle_measured.csv") rows)"

say "diagnose: what the nominal model gets wrong, and why"
"$stray" diagnose "$out/baffle_measured.csv" --scene ref4 \
	--rays $((rays / 5)) --threads 2 --plot "$out/diagnose.png" \
	--json > "$out/diagnose.json"
# The named causes that belong to the baffle become the corrected model.
corrections=$(python3 - "$out/diagnose.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
keys = {"reflectance": ("reflectance", "reflectance"),
        "knife_edge_radius": ("edge_radius", "radius_mm")}
out = []
for c in d["causes"] if d.get("explained", True) else []:
    if c["name"] in keys:
        k, p = keys[c["name"]]
        out.append("--set %s=%.4g" % (k, c["params"][p]))
    elif c["name"] == "bevel_face":
        out.append("--set bevel_face=upper")
print(" ".join(out))
PY
)
python3 - "$out/diagnose.json" <<'PY' | tee "$out/diagnose.txt"
import json, sys
d = json.load(open(sys.argv[1]))
print("discrepancy significant: %s; explained: %s" % (d["significant"], d.get("explained")))
for c in d["causes"]:
    for k, v in c["params"].items():
        lo, hi = c.get("intervals", {}).get(k, [float("nan")] * 2)
        print("  cause %-18s %s = %.4g  [%.4g, %.4g]" % (c["name"], k, v, lo, hi))
print("RMS log10 residual %.3f -> %.3f (%.0fx)" % (d["rms_before"], d["rms_after"],
      d["rms_before"] / max(d["rms_after"], 1e-12)))
PY
echo "corrected model: ${corrections:-(nothing to correct)}"

say "diagnose (system): a baffle + lens sweep, the lens's causes apart from the baffle's"
# Truth: the coating and edges above, behind the flight unit of the lens
# (barrel blackened, a field stop added) that passes 1 % of the lab unit's
# light beyond its field; the analysis is told the lab unit's table
# (lens.csv) and the nominal baffle (issue 17 item 3).
awk -F, '/^[0-9]/ { if ($2 < 0.5) $2 *= 0.01; print $1 "," $2; next }
	/^theta/ { print "theta_deg,alpha" }' OFS=, "$out/lens.csv" \
	> "$out/lens_flight.csv"
"$stray" trace --scene ref4 --set reflectance=0.08 --set edge_radius=0.05 \
	--lens "$out/lens_flight.csv" --angles "0:85:$step_deg" --rays "$rays" \
	--seed 4243 --out "$out/system_truth.csv" > /dev/null
"$stray" photometer --truth "$out/system_truth.csv" --floor 0 \
	--detect-floor 1e-11 --out "$out/system_measured.csv" --seed 8
"$stray" diagnose "$out/system_measured.csv" --scene ref4 \
	--lens "$out/lens.csv" --rays $((rays / 5)) --threads 2 \
	--plot "$out/diagnose_system.png" --json > "$out/diagnose_system.json"
python3 - "$out/diagnose_system.json" <<'PY' | tee "$out/diagnose_system.txt"
import json, sys
d = json.load(open(sys.argv[1]))
print("system curve (baffle + lens %s): significant %s, explained %s"
      % (d.get("lens"), d["significant"], d.get("explained")))
for c in d["causes"]:
    for k, v in c["params"].items():
        lo, hi = c.get("intervals", {}).get(k, [float("nan")] * 2)
        print("  cause %-18s (%s) %s = %.4g  [%.4g, %.4g]"
              % (c["name"], c.get("side", "?"), k, v, lo, hi))
print("RMS log10 residual %.3f -> %.3f" % (d["rms_before"], d["rms_after"]))
f = lambda x: "not excluded within the sweep" if x is None else "%.1f deg" % x
print("Sun exclusion before/after: %s -> %s"
      % (f(d.get("sun_deg_before")), f(d.get("sun_deg_after"))))
PY

say "exclusion: Sun, Moon and Earth-limb angles, nominal and corrected (fig. 5.1)"
"$stray" trace --scene ref4 $corrections --lens "$out/lens.csv" \
	--rays "$rays" --out "$out/system_corrected.csv" > /dev/null
{ echo "Nominal model (4 % coating, sharp edges):"
  "$stray" exclusion --curve "$out/system.csv" --earth-albedo 0.3 2>&1
  echo; echo "Corrected by the diagnosis ($corrections):"
  "$stray" exclusion --curve "$out/system_corrected.csv" --earth-albedo 0.3 \
	--plot "$out/exclusion.png" 2>&1; } | tee "$out/exclusion.txt"
"$stray" exclusion --curve "$out/system_corrected.csv" --earth-albedo 0.3 \
	--json > "$out/exclusion.json" 2>/dev/null

say "design variant: the path analysis blames the vane bevels; flip them"
"$stray" trace --scene ref4 $corrections --set bevel_face=upper \
	--lens "$out/lens.csv" --rays "$rays" \
	--out "$out/system_variant.csv" > /dev/null
{ echo; echo "Variant: bevels on the upper faces (corrected model, --set bevel_face=upper):"; } |
	tee -a "$out/exclusion.txt"
"$stray" exclusion --curve "$out/system_variant.csv" --earth-albedo 0.3 \
	--plot "$out/exclusion_variant.png" 2>&1 | tee -a "$out/exclusion.txt"

say "pixels: what the thesis model gets wrong about pixels (docs/normalisation.md, docs/frames.md)"
# Every demo curve's exclusion angles under the thesis's k_px = 1 and the
# consistent k_px, with stray light uniform and as the lab's region map.
for c in system system_corrected system_variant; do
	for n in thesis consistent; do
		"$stray" exclusion --curve "$out/$c.csv" --normalisation "$n" \
			--json > "$out/pixels_${c}_${n}_uniform.json" 2>/dev/null
		"$stray" exclusion --curve "$out/$c.csv" --normalisation "$n" \
			--map "$out/lens_map.csv" \
			--json > "$out/pixels_${c}_${n}_mapped.json" 2>/dev/null
	done
done
# Every demo system's Sun exclusion angle under every model (issue 28):
# the thesis (k_px = 1), consistent, and each validated detector with the
# failure mode that sets it (stray exclusion --models).
for c in system system_corrected system_variant; do
	"$stray" exclusion --curve "$out/$c.csv" --models \
		--json > "$out/models_${c}.json" 2>/dev/null
done
# Where the variant's stray light lands at 40 deg: out of the field, so
# spread by the lens's own measured region map.
"$stray" trace --scene ref4 $corrections --set bevel_face=upper \
	--lens "$out/lens.csv" --lens-map "$out/lens_map.csv" --angles 40 \
	--rays "$rays" --focal-map "$out/focal_map.fits" \
	--focal-map-png "$out/focal_map.png" --map-angle 40 \
	--json > "$out/focal_map.json"
# The FDR model against rendered frames and two star detectors.
VALIDATE_WINDOW=${DEMO_FRAMES:-} VALIDATE_MAP="$out/focal_map.fits" \
	scripts/validate-frames.sh "$build" "$out/frames" > "$out/validation.md"
cp "$out/frames/validation.png" "$out/validation.png"
# A 512 px corner of a frame at the tolerated rate's attenuation: stars,
# stray light and noise at a scale the eye can read.
"$stray" frames --alpha 3e-7 --window 512 --seed 11 \
	--png "$out/frame_sample.png" > /dev/null
python3 scripts/demo_pixels.py "$out" | tee "$out/pixels.txt"

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

say "availability: three heads on a nadir-pointing, yaw-steering spacecraft (CCSDS OEM/AEM)"
# The demo mission written as OEM/AEM and read back; heads 40 deg off the
# zenith to either side of the track and one towards the wake.
cat > "$out/heads.json" <<'EOF'
{"heads": [
 {"name": "A", "boresight_body": [0, 0.6428, -0.7660], "up_body": [1, 0, 0], "table": "flight_table.bin"},
 {"name": "B", "boresight_body": [0, -0.6428, -0.7660], "up_body": [1, 0, 0], "table": "flight_table.bin"},
 {"name": "C", "boresight_body": [-0.6428, 0, -0.7660], "up_body": [0, 1, 0], "table": "flight_table.bin"}
]}
EOF
"$stray" availability --write-oem "$out/mission.oem" --write-aem "$out/mission.aem" \
	--hours "${DEMO_MISSION_HOURS:-24}"
"$stray" availability --oem "$out/mission.oem" --aem "$out/mission.aem" \
	--heads "$out/heads.json" --plot "$out/availability" \
	--out "$out/availability.csv" | tee "$out/availability.txt"
"$stray" availability --oem "$out/mission.oem" --aem "$out/mission.aem" \
	--heads "$out/heads.json" --json > "$out/availability.json"

say "flightcheck: the tracker in orbit, seen from its own images (thesis §4.3)"
# Flight frames (synthetic: make_flight, the test's generator) along an AEM
# sweep of the Sun angle, 30-85 deg.  Hidden from the analysis: the stray
# light is 1.7x the model's level and the coating reflects 8 %, not 4 %.
# Model and truth are ref4 traces behind a flat lens transmission of 2e-3.
"$stray" trace --scene ref4 --angles 0,30:86:5 --rays 300000 \
	--out "$out/fc_ref4.csv" > /dev/null
"$stray" trace --scene ref4 --angles 0,30:86:5 --rays 300000 \
	--set reflectance=0.08 --out "$out/fc_ref4_r08.csv" > /dev/null
for c in fc_ref4 fc_ref4_r08; do
	awk -F, '/^#/ || /^theta/ { next } $1 > 0 { printf "%s,%.10g\n", $1, 2e-3 * $2 }
		BEGIN { print "theta_deg,alpha" }' "$out/$c.csv" > "$out/${c}_lens.csv"
done
# Full frames even in the small demo (~4 s): windows calibrate by luck.
# With 512-1024 px windows 4-8 of the 10-35 stars that cannot be missed
# were found (at least 30 % needed) for truth curves of seeds 2 and 3
# and with light-side paths; the seed-1 detector-side curve passed at
# 512 px.  Full frames passed with all of them.
fc_px=0
"$build/tests/flightcheck/make_flight" "$out/flight_frames" "$out/flight.aem" \
	"$out/fc_ref4_r08_lens.csv" 1.7 12 "$fc_px" 30 85
"$stray" flightcheck "$out/flight_frames" --aem "$out/flight.aem" \
	--model "$out/fc_ref4_lens.csv" --out "$out/flight_curve.csv" \
	--plot "$out/flightcheck.png" | tee "$out/flightcheck.txt"
"$stray" flightcheck "$out/flight_frames" --aem "$out/flight.aem" \
	--model "$out/fc_ref4_lens.csv" --json > "$out/flightcheck.json"
{ echo; echo "stray diagnose on the flight curve (scale free; the model's lens T = 2e-3 is in the scale):"
  "$stray" diagnose "$out/flight_curve.csv" --scene ref4 --rays 300000 \
	--threads 2 --plot "$out/flightcheck_diagnose.png" 2>/dev/null
  echo "hidden truth: scale 1.7 (x T = 3.4e-3, log10 -2.469), reflectance 0.08"
} | tee -a "$out/flightcheck.txt"
rm -rf "$out/flight_frames"	# 12 full frames: 120 MB
# The sky as it is (issue 24): the shipped Hipparcos extract with the stars'
# colours and proper motion, exposures of 0.05-0.2 s, a 1.6 e-/DN gain and a
# 180 DN bias (BIAS, GAIN keywords), times in TT; hidden scale 1.7 again.
"$build/tests/flightcheck/make_flight" "$out/flight_sky" "$out/flight_sky.aem" \
	"$out/fc_ref4_lens.csv" 1.7 12 0 30 85 libstray/data/hip2_hp6.5.dat
{ echo; echo "the real sky (Hipparcos I/311 extract; hidden: scale 1.7, DN/e- 1/1.6 = 0.625):"
  "$stray" flightcheck "$out/flight_sky" --aem "$out/flight_sky.aem" \
	--model "$out/fc_ref4_lens.csv" --catalogue libstray/data/hip2_hp6.5.dat
} | tee -a "$out/flightcheck.txt"
rm -rf "$out/flight_sky"	# 12 full frames: 120 MB

say "review: the demo's system and two user projects, each from its project file (stray review, docs/review.md)"
# First the demo's own system as a project file (the same lab sweep, lab
# curve, mission and heads): its photometry, FDR, lens, diagnosis and
# mission are the steps above number for number (checked below); its
# system curve is traced on 1-deg rows (the flight table's limit) and its
# flight table is the nominal system's, not the variant's.
cat > "$out/project.json" <<EOF
{
  "name": "st16-like behind ref4, the built-in reference system",
  "sensor": "st16-like",
  "scene": "ref4",
  "lens": {"sweep": "sweep"},
  "requirements": {"false_stars_per_image": 5, "sun_exclusion_deg_max": 40,
                   "moon_exclusion_deg_max": 20, "earth_exclusion_deg_max": 30,
                   "availability_min": 0.9},
  "measured": {"curve": "baffle_measured.csv", "kind": "baffle"},
  "mission": {"orbit": {"altitude_km": 550, "ltan": "22:30", "epoch": "2026-06-21",
                        "hours": ${DEMO_MISSION_HOURS:-24}}, "attitude": "nadir"},
  "heads": [
    {"name": "A", "boresight_body": [0, 0.6428, -0.7660], "up_body": [1, 0, 0]},
    {"name": "B", "boresight_body": [0, -0.6428, -0.7660], "up_body": [1, 0, 0]},
    {"name": "C", "boresight_body": [-0.6428, 0, -0.7660], "up_body": [0, 1, 0]}]
}
EOF
"$stray" review "$out/project.json" --out "$out/review" --rays "$rays" 2>&1 |
	grep -v "s so far"
"$stray" exclusion --curve "$out/system.csv" --earth-albedo 0.3 \
	--json > "$out/exclusion_nominal.json" 2>/dev/null
python3 - "$out" <<'PY' | tee "$out/review_vs_demo.txt"
import filecmp, json, os, sys
o = sys.argv[1]
j = lambda *p: json.load(open(os.path.join(o, *p)))
def same(a, b):		# timing and provenance aside
    for d in (a, b):
        for k in [k for k in d if k == "provenance" or k.endswith("seconds")]:
            d.pop(k)
    return "same" if a == b else "DIFFERENT"
rows = lambda *p: [l for l in open(os.path.join(o, *p)) if not l.startswith("#")]
both = lambda n: filecmp.cmp(os.path.join(o, n), os.path.join(o, "review", n), False)
print("review of the demo's system against the demo's own steps:")
print("  photometry: %s; fdr: %s" % (same(j("photometry.json"), j("review", "photometry.json")),
      same(j("fdr_sun.json"), j("review", "fdr.json"))))
print("  lens curve (rows): %s" % ("same" if rows("lens.csv") == rows("review", "lens.csv") else "DIFFERENT"))
print("  diagnosis: %s" % same(j("diagnose.json"), j("review", "diagnose.json")))
print("  mission OEM/AEM: %s" % ("same" if both("mission.oem") and both("mission.aem") else "DIFFERENT"))
f = lambda x: "not excluded" if x is None else "%.2f deg" % x
a, b = j("exclusion_nominal.json"), j("review", "exclusion.json")
for k in ("sun_deg", "moon_deg", "earth_limb_deg"):
    print("  nominal system %-15s demo (auto angles) %-14s review (1-deg rows) %s" % (k, f(a[k]), f(b[k])))
PY
if command -v chromium >/dev/null; then
	scripts/check-report.sh "$out/review" --complete
fi
# Then two user projects unlike it:
# five thin vanes behind an ideal lens on a 500 km sun-synchronous orbit,
# and three upper-bevel vanes with a lens curve, a lab curve to diagnose
# and an inclined inertial mission: each report names only its project.
for p in cube navcam; do
	"$stray" review "examples/review-$p/project.json" --out "$out/review-$p" \
		--rays $((rays / 5)) 2>&1 | grep -v "s so far"
	python3 - "$out/review-$p/review.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for v in d["verdicts"]:
    f = "none" if v["found"] is None else "%.4g" % v["found"]
    print("  %-26s required %-6g found %-10s %s  %s" % (v["requirement"], v["required"],
          f, v["unit"], "PASS" if v["pass"] else "FAIL"))
PY
	if command -v chromium >/dev/null; then
		scripts/check-report.sh "$out/review-$p" --complete
	fi
done

say "report: $out/report.html (and report.md)"
"$stray" report "$out"
if command -v chromium >/dev/null; then
	scripts/check-report.sh "$out"
fi
echo "demo: done in $(( $(date +%s) - start )) s; open $out/report.html"
