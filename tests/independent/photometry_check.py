#!/usr/bin/env python3
"""An independent computation of the st16-like reference fluxes (thesis
eq. 2.1-2.2) from the same shipped spectra, sharing no code with libstray:
plain Python, the trapezoid rule on the union of the two wavelength grids,
each curve linear between its samples and zero outside them.

    python3 tests/independent/photometry_check.py [DATA_DIR]

prints JSON with the keys of `stray photometry --json`.
"""
import bisect
import json
import os
import sys

H = 6.62607015e-34
C = 299792458.0


def read_curve(path):
    xs, ys = [], []
    header = False
    with open(path) as fh:
        for line in fh:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            if not header:
                header = True
                continue
            x, y = line.split(",")
            xs.append(float(x))
            ys.append(float(y))
    return xs, ys


def at(curve, x):
    xs, ys = curve
    if x < xs[0] or x > xs[-1]:
        return 0.0
    i = bisect.bisect_right(xs, x) - 1
    if i >= len(xs) - 1:
        return ys[-1]
    t = (x - xs[i]) / (xs[i + 1] - xs[i])
    return ys[i] + t * (ys[i + 1] - ys[i])


def photon_flux(src, resp):
    lo = max(src[0][0], resp[0][0])
    hi = min(src[0][-1], resp[0][-1])
    grid = sorted({x for x in src[0] + resp[0] if lo <= x <= hi})
    # Split each union interval in 8 so the trapezoid error is small.
    total = 0.0
    for a, b in zip(grid, grid[1:]):
        step = (b - a) / 8.0
        for k in range(8):
            x0, x1 = a + k * step, a + (k + 1) * step
            g0 = at(src, x0) * at(resp, x0) * x0
            g1 = at(src, x1) * at(resp, x1) * x1
            total += 0.5 * (g0 + g1) * (x1 - x0)
    return total * 1e-9 / (H * C)


def main():
    data = sys.argv[1] if len(sys.argv) > 1 else "libstray/data"
    qe = read_curve(os.path.join(data, "qe_mt9p031_approx.csv"))
    sun = photon_flux(read_curve(os.path.join(data, "sun_am0_astm_e490.csv")), qe)
    vega = photon_flux(read_curve(os.path.join(data, "vega_calspec_alpha_lyr_stis_011.csv")), qe)
    zero = vega * 10 ** (0.4 * 0.03)
    print(json.dumps({
        "sun": sun,
        "vega": vega,
        "zero_mag": zero,
        "moon": zero * 10 ** (0.4 * 12.6),
        "drs": zero * 10 ** (-0.4 * 5.75),
    }))


if __name__ == "__main__":
    main()
