#!/usr/bin/env python3
"""footprint.py - the firmware footprint report of `make firmware`.

Sizes per part (the module, libstray's compiled-in core, newlib/libgcc)
from the linker map; the worst-case stack of fdrfw_frame and fdrfw_init
over the static call graph from GCC's -fcallgraph-info=su (.ci files);
functions GCC knows no stack for (newlib's libm, libgcc) are listed, the
emulated run's painted high-water mark covers them.

Usage: footprint.py OBJ_DIR MAP_FILE [--check]
With --check, exit 1 when the flight code (the module and the libstray core
compiled into it) passes 8 KiB, its static RAM 64 B, or the static stack
of fdrfw_frame or fdrfw_init 512 B (issue #6's budgets; newlib's libm is
reported beside them, see README.md).
"""
import os
import re
import sys

BUDGET_CODE = 8 * 1024
BUDGET_RAM = 64
BUDGET_STACK = 512
# stray_root_brent calls its function argument: the callback each caller
# passes it (libstray/core/fdr.c, tail.c).
BRENT = "stray_root_brent"
CALLBACK = {"stray_gauss_q_inv": "libstray/core/tail.c:q_inv_residual",
            "stray_fdr_threshold": "libstray/core/fdr.c:drs_residual",
            "stray_fdr_alpha_required": "libstray/core/fdr.c:req_residual"}
# (root, functions left out).  An exposure change is a closed form
# (fdrfw_set_exposure, on the frame's path); the root search of eq. 2.16
# runs once, in fdrfw_init.
ROOTS = [("fdrfw_frame", ()), ("fdrfw_set_exposure", ()), ("fdrfw_init", ())]
# Parts whose code is ours: the budget is theirs; libm is reported apart.
FLIGHT = ("firmware_fdr", "libstray core")

NODE = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
EDGE = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')
BYTES = re.compile(r'\\n(\d+) bytes \((static|dynamic[^)]*)\)')


def read_graph(obj_dir):
    stack, calls = {}, {}
    for root, _, files in os.walk(obj_dir):
        for name in files:
            if not name.endswith(".ci"):
                continue
            with open(os.path.join(root, name)) as f:
                for line in f:
                    m = NODE.search(line)
                    if m:
                        b = BYTES.search(m.group(2))
                        if b:
                            stack[m.group(1)] = (int(b.group(1)), b.group(2))
                        continue
                    m = EDGE.search(line)
                    if m:
                        calls.setdefault(m.group(1), set()).add(m.group(2))
    return stack, calls


def worst(fn, g, path, caller, prune):
    """Deepest stack below fn: (bytes, call path); DFS, no recursion in
    the graph (the module has none: a cycle stops the report)."""
    stack, calls, unknown = g
    if fn in path:
        raise SystemExit("footprint: recursion through %s" % fn)
    own = stack.get(fn, (0, "unknown"))[0]
    if fn not in stack:
        unknown.add(fn)
    targets = set(calls.get(fn, ()))
    if fn == BRENT:
        targets.add(CALLBACK.get(caller, "__indirect_call"))
    best, best_path = 0, []
    for callee in sorted(targets):
        if callee.startswith("__indirect") or callee in prune:
            continue
        depth, sub = worst(callee, g, path | {fn}, fn, prune)
        if depth > best:
            best, best_path = depth, sub
    return own + best, [fn] + best_path


SECTION = re.compile(r'^ (\.(text|rodata|data|bss)[^\s]*)\s*(?:\n\s+)?'
                     r'(0x[0-9a-f]+)\s+(0x[0-9a-f]+)\s+(\S+)', re.M)


def part_of(obj):
    if "flight_table" in obj:
        return "flight table"
    if "/firmware_fdr/target/" in obj:
        return "harness (startup)"
    if "/firmware_fdr/" in obj:
        return "firmware_fdr"
    if "/libstray/core/" in obj:
        return "libstray core"
    return "newlib libm/libc, libgcc"


def sizes(map_file):
    with open(map_file) as f:
        text = f.read()
    text = text.split("Linker script and memory map", 1)[-1]
    parts = {}
    for m in SECTION.finditer(text):
        size = int(m.group(4), 16)
        if size == 0 or int(m.group(3), 16) == 0 and m.group(2) != "text":
            continue
        kind = m.group(2)
        p = parts.setdefault(part_of(m.group(5)),
                             {"text": 0, "rodata": 0, "data": 0, "bss": 0})
        p[kind] += size
    return parts


def soft_double(map_file):
    """libgcc's double-precision routines the image links (the M4F's FPU
    is single precision: each is software)."""
    with open(map_file) as f:
        text = f.read().split("Linker script and memory map", 1)[-1]
    found = set(re.findall(r'\s(__aeabi_(?:d\w+|f2d|[il]2d|ui2d))\s', text))
    return sorted(found)


def main():
    obj_dir, map_file = sys.argv[1], sys.argv[2]
    parts = sizes(map_file)
    print("footprint (arm-none-eabi, -Os, Cortex-M4F), bytes:")
    print("  %-26s %7s %7s %7s %7s" % ("part", ".text", ".rodata",
                                        ".data", ".bss"))
    total = {"text": 0, "rodata": 0, "data": 0, "bss": 0}
    for name in sorted(parts):
        p = parts[name]
        print("  %-26s %7d %7d %7d %7d" % (name, p["text"], p["rodata"],
                                            p["data"], p["bss"]))
        for k in total:
            total[k] += p[k]
    print("  %-26s %7d %7d %7d %7d" % ("total", total["text"],
                                        total["rodata"], total["data"],
                                        total["bss"]))
    zero = {"text": 0, "rodata": 0, "data": 0, "bss": 0}
    code = sum(parts.get(n, zero)["text"] for n in FLIGHT)
    ram = sum(parts.get(n, zero)["data"] + parts.get(n, zero)["bss"]
              for n in FLIGHT)
    lib = parts.get("newlib libm/libc, libgcc", zero)
    print("  flight code (firmware_fdr + libstray core) %d B (budget %d); "
          "its static RAM %d B (budget %d)" % (code, BUDGET_CODE, ram,
                                               BUDGET_RAM))
    print("  whole image code %d B, of it newlib libm/libc and libgcc "
          "%d B; soft-double routines: %s"
          % (total["text"], lib["text"], ", ".join(soft_double(map_file))
             or "none"))
    over = code > BUDGET_CODE or ram > BUDGET_RAM
    stack, calls = read_graph(obj_dir)
    for root, prune in ROOTS:
        unknown = set()
        depth, path = worst(root, (stack, calls, unknown), set(), None,
                            set(prune))
        print("worst-case stack of %s%s: %d B (budget %d) via %s"
              % (root, " without " + ", ".join(prune) if prune else "",
                 depth, BUDGET_STACK, " > ".join(
                     p.split(":")[-1] for p in path)))
        lib = sorted(u for u in unknown if not u.startswith("__aeabi"))
        print("  not counted (no -fstack-usage: newlib/libgcc): %s"
              % ", ".join(lib))
        over = over or depth > BUDGET_STACK
    if "--check" in sys.argv[3:] and over:
        print("footprint: over budget")
        sys.exit(1)


if __name__ == "__main__":
    main()
