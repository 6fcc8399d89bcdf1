#!/usr/bin/env python3
"""The demo's "pixels" step: tables from the artifacts scripts/demo.sh
left in OUT (exclusion --json per curve x normalisation x stray light, the
focal map's --json, the validation points of scripts/validate-frames.sh).
Writes OUT/pixels.json (for `stray report`) and prints OUT/pixels.txt.
Usage: scripts/demo_pixels.py OUT"""
import glob
import json
import os
import sys

out = sys.argv[1]
SYSTEMS = [("system", "nominal"), ("system_corrected", "corrected"),
           ("system_variant", "variant (bevels up)")]


def load(name):
    with open(os.path.join(out, name)) as f:
        return json.load(f)


def deg(x):
    return None if x is None else round(x, 2)


def show(x):
    return "none" if x is None else "%.2f" % x


COLS = [("thesis", "uniform", "Sun k_px=1"),
        ("thesis", "mapped", "Sun k_px=1 mapped"),
        ("consistent", "uniform", "Sun consistent"),
        ("consistent", "mapped", "Sun consistent mapped")]
rows, k_px = [], None
for key, label in SYSTEMS:
    row = {"system": label}
    for n, light, col in COLS:
        d = load("pixels_%s_%s_%s.json" % (key, n, light))
        row[col] = deg(d.get("sun_deg"))
        if n == "consistent":
            k_px = d["k_px"]
    for n, col in (("thesis", "Moon k_px=1"), ("consistent", "Moon consistent")):
        row[col] = deg(load("pixels_%s_%s_uniform.json" % (key, n)).get("moon_deg"))
    rows.append(row)

# Every system's Sun angle per model and what sets it (exclusion --models).
by_model = []
for key, label in SYSTEMS:
    for m in load("models_%s.json" % key)["models"]:
        by_model.append({
            "system": label, "model": m["model"],
            "alpha_required": m["alpha_required"],
            "Sun deg": deg(m.get("sun_deg")),
            "set by": m["binding"].replace("_", " ")})

fm = load("focal_map.json").get("focal_map", {})
points, size = [], "-"
for path in glob.glob(os.path.join(out, "frames", "*-*.json")):
    label = os.path.basename(path).split("-")[0]
    d = load(os.path.relpath(path, out))
    t = d["detectors"]
    points.append({
        "light": {"thesis": "uniform, k_px = 1"}.get(label, label),
        "alpha": d["alpha"], "e-/px": round(d["stray_e_per_px"]),
        "frames": d["frames"], "model eq. 2.18": t["thesis"]["model_fdr"],
        "window: extended": t["thesis"]["model_fdr_extended"],
        "window: measured": "%.3g ± %.2g" % (
            t["thesis"]["false_stars_per_image"],
            t["thesis"]["false_stars_sigma"]),
        "threshold: extended": t["threshold"]["model_fdr_extended"],
        "threshold: measured": "%.3g ± %.2g" % (
            t["threshold"]["false_stars_per_image"],
            t["threshold"]["false_stars_sigma"])})
    size = "%d x %d" % (d["cols"], d["rows"])
order = {"uniform": 0, "mapped": 1}
points.sort(key=lambda p: (order.get(p["light"], 2), p["alpha"]))

doc = {
    "k_px": k_px,
    "exclusion_what": "deg; k_px = 1 (thesis) or A_cs/(n_tot A_px) "
                      "(consistent); stray light uniform or mapped by "
                      "lens_map.csv",
    "frame_px": size,
    "focal_map.theta_deg": fm.get("theta_deg"),
    "focal_map.mean_per_px": fm.get("mean"),
    "focal_map.in_field_fraction": fm.get("in_field_fraction"),
    "focal_map.spread": fm.get("spread"),
    "exclusion": rows,
    "exclusion_by_model": by_model,
    "validation": points,
}
with open(os.path.join(out, "pixels.json"), "w") as f:
    json.dump(doc, f, indent=1)

print("Sun exclusion angle, deg (Moon in the last two columns), k_px = %.3f"
      % k_px)
print("%-22s %10s %10s %10s %10s %8s %8s" % (
    "system", "thesis", "thesis", "consist.", "consist.", "moon", "moon"))
print("%-22s %10s %10s %10s %10s %8s %8s" % (
    "", "uniform", "mapped", "uniform", "mapped", "thesis", "consist."))
for r in rows:
    print("%-22s %10s %10s %10s %10s %8s %8s" % ((r["system"],) + tuple(
        show(r[c]) for c in [c for _, _, c in COLS] +
        ["Moon k_px=1", "Moon consistent"])))
print()
print("Sun exclusion angle per model, deg, and the failure mode that sets it")
for r in by_model:
    print("%-22s %-28s %10.3g %8s  %s" % (
        r["system"], r["model"], r["alpha_required"], show(r["Sun deg"]),
        r["set by"]))
print()
print("Focal map of the variant at %s deg: mean %.3g per pixel (= k_px alpha), "
      "%.1f %% imaged in the field, out-of-field light spread by the %s"
      % (fm.get("theta_deg"), fm.get("mean", float("nan")),
         100 * fm.get("in_field_fraction", float("nan")),
         "lens region map" if fm.get("spread") == "lensmap" else "uniform"))
print()
print("False stars per frame, rendered frames against the model (eq. 2.18, "
      "Poisson + read noise) and its extension")
print("%-18s %8s %7s %6s %9s | %9s %16s | %9s %16s" % (
    "light", "alpha", "e-/px", "frames", "model", "win. ext", "window measured",
    "thr. ext", "thresh. measured"))
for p in points:
    print("%-18s %8.3g %7.0f %6d %9.3g | %9.3g %16s | %9.3g %16s"
          % (p["light"], p["alpha"], p["e-/px"], p["frames"],
             p["model eq. 2.18"], p["window: extended"],
             p["window: measured"], p["threshold: extended"],
             p["threshold: measured"]))
print("(%s px per frame; 'window' is the thesis's window-sum detector, "
      "'thresh.' the k-sigma threshold detector open trackers use)" % size)
