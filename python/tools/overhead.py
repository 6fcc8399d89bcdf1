"""The overhead of a Python call against the CLI (docs/python.md): the
same trace and frame render, alternating pairs (CLI as a process, Python
in-process), median and min-max wall time of each.  Usage:
overhead.py STRAY_BIN [pairs]"""
import statistics
import subprocess
import sys
import time

import straylight as sl

stray, pairs = sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 7
cases = {
    "trace ref4, 19 angles, 20k paths, 1 thread": (
        ["trace", "--scene", "ref4", "--angles", "0:90:5", "--rays", "20000",
         "--seed", "1", "--threads", "1"],
        lambda: sl.trace("ref4", angles="0:90:5", rays=20000, seed=1,
                         threads=1)),
    "frames 1 x 256x256, Sun 35 deg": (
        ["frames", "--alpha", "1e-6", "--theta", "35", "--frames", "1",
         "--window", "256", "--seed", "7"],
        lambda: sl.frames(alpha=1e-6, theta=35, frames=1, window=256,
                          seed=7)),
    "photometry (no work: the fixed cost)": (
        ["photometry"], lambda: sl.photometry()),
}
for name, (args, py) in cases.items():
    c, p = [], []
    for _ in range(pairs):
        t = time.perf_counter()
        subprocess.run([stray, "--json", *args], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        c.append(time.perf_counter() - t)
        t = time.perf_counter()
        py()
        p.append(time.perf_counter() - t)
    d = [b - a for a, b in zip(c, p)]
    ms = lambda v: f"{1e3 * statistics.median(v):.1f} ms ({1e3 * min(v):.1f}-{1e3 * max(v):.1f})"
    print(f"{name}: CLI {ms(c)}, Python {ms(p)}, Python - CLI {ms(d)}")
