#!/usr/bin/env python3
"""frames_map.py KIND OUT.fits [AMP] - a focal-plane map for `stray frames --map`
(float FITS, BITPIX -32, 72 x 54 cells of 36 px over the st16-like
2592 x 1944 px detector; stray frames resamples it bilinearly and scales it
to mean 1).  KIND:
  ramp    0.4-1.6 along columns, 0.8-1.2 along rows (docs/frames.md's map:
          a tile background follows it, no background-error term)
  ripple  1 + AMP sin(2 pi x / 256 px) sin(2 pi y / 256 px) on the ramp
          (AMP 0.005):
          structure at twice the 128 px tiles, which their bilinear
          background cannot follow (issue 28: the map term)
"""
import math
import struct
import sys

NX, NY, CELL = 72, 54, 36


def value(kind, i, j, amp):
    x, y = (i + 0.5) * CELL, (j + 0.5) * CELL
    ramp = (0.4 + 1.2 * (i + 0.5) / NX) * (0.8 + 0.4 * (j + 0.5) / NY)
    if kind == "ramp":
        return ramp
    return ramp * (1.0 + amp * math.sin(2 * math.pi * x / 256.0) *
                   math.sin(2 * math.pi * y / 256.0))


def main():
    kind, out = sys.argv[1], sys.argv[2]
    amp = float(sys.argv[3]) if len(sys.argv) > 3 else 0.005
    if kind not in ("ramp", "ripple"):
        sys.exit("frames_map.py: KIND must be ramp or ripple")
    cards = ["SIMPLE  =                    T", "BITPIX  =                  -32",
             "NAXIS   =                    2", "NAXIS1  = %20d" % NX,
             "NAXIS2  = %20d" % NY, "END"]
    hdr = "".join(c.ljust(80) for c in cards).ljust(2880).encode()
    data = b"".join(struct.pack(">f", value(kind, i, j, amp))
                    for j in range(NY) for i in range(NX))
    data += b"\0" * (-len(data) % 2880)
    with open(out, "wb") as f:
        f.write(hdr + data)


main()
