#!/usr/bin/env python3
"""compare_frames.py SIM_DIR REAL_DIR - the two sweeps' frames, file by
file: the FITS data units must be byte-identical, the headers may differ
only in the keywords named below (times, and MONITOR: the photodiode's
noise hash is per read, and reads are the same sequence, so it should
match too - listed when it does not).  Prints one summary line; exit 1 on
any difference in data, a missing or extra frame."""
import os
import sys

VOLATILE = {b"DATE", b"DATE-OBS", b"DATE-BEG", b"DATE-END", b"CREATED"}


def split_fits(path):
    with open(path, "rb") as f:
        raw = f.read()
    cards = []
    for off in range(0, len(raw), 80):
        card = raw[off:off + 80]
        cards.append(card)
        if card.startswith(b"END") and card[3:].strip() == b"":
            hdr_end = (off // 2880 + 1) * 2880
            return cards, raw[hdr_end:]
    raise ValueError(f"{path}: no END card")


def frames(d):
    return sorted(n for n in os.listdir(d) if n.endswith(".fits"))


def main():
    sim, real = sys.argv[1], sys.argv[2]
    a, b = frames(sim), frames(real)
    if a != b:
        print(f"compare_frames: frame lists differ: {len(a)} vs {len(b)}; "
              f"only in sim {sorted(set(a) - set(b))[:3]}, "
              f"only in real {sorted(set(b) - set(a))[:3]}")
        return 1
    bad, hdr_diff, nbytes = [], set(), 0
    for name in a:
        ca, da = split_fits(os.path.join(sim, name))
        cb, db = split_fits(os.path.join(real, name))
        nbytes += len(da)
        if da != db:
            bad.append(name)
        for x, y in zip(ca, cb):
            if x != y:
                key = x[:8].strip()
                if key not in VOLATILE:
                    hdr_diff.add(key.decode())
    print(f"compare_frames: {len(a)} frames, {nbytes} data bytes: "
          f"{len(a) - len(bad)} identical, {len(bad)} differ"
          + (f" (first {bad[0]})" if bad else "")
          + (f"; header keywords differing: {sorted(hdr_diff)}"
             if hdr_diff else "; headers identical but for dates"))
    return 1 if bad or not a else 0


if __name__ == "__main__":
    sys.exit(main())
