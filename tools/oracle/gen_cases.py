#!/usr/bin/env python3
"""Random and edge-case tessellator cases for the llvmpipe oracle (tessref's input format).

gen_cases.py COUNT SEED > cases.txt

Each line: DOMAIN SPACING WINDING MODE O0 O1 O2 O3 I0 I1 (GL names, see shared/bench/README.md).
A quarter of the factors come from a list of edge cases (culling values, clamp bounds, ties at
n + 2^-17, the fractional_even fold windows above 6 and 30, inner = 1); the rest are random,
mostly small (so dumps stay small), sometimes up to 70. The same COUNT and SEED give the same file.
"""
import random
import struct
import sys

DOMAINS = ["quads", "triangles", "isolines"]
SPACINGS = ["equal_spacing", "fractional_odd_spacing", "fractional_even_spacing"]
SPECIAL = ["nan", "inf", "-inf", "-0", "0", "-1", "1", "2", "3", "63", "64", "65", "1000",
           "1.0000076", "1.00001526", "3.0000076", "5.0000076", "4.0000076", "6.0000081", "6.00005",
           "6.0001", "30.0000095", "30.003", "30.0063248", "14.0001", "62.0001", "7", "53", "1e-30", "2.5"]


def f32(x):
    """Rounds to float32 and prints it exactly (9 significant digits round-trip)."""
    return "%.9g" % struct.unpack("<f", struct.pack("<f", x))[0]


def factor(rng):
    r = rng.random()
    if r < 0.25:
        return rng.choice(SPECIAL)
    if r < 0.85:
        return f32(rng.uniform(0.5, 12.0))
    if r < 0.95:
        return str(rng.randint(1, 20))
    return f32(rng.uniform(0.5, 70.0))


def main():
    count, seed = int(sys.argv[1]), int(sys.argv[2])
    rng = random.Random(seed)
    for _ in range(count):
        domain = rng.choice(DOMAINS)
        spacing = rng.choice(SPACINGS)
        winding = rng.choice(["ccw", "cw"])
        mode = "points" if rng.random() < 0.3 else "prims"
        fs = [factor(rng) for _ in range(6)]
        if rng.random() < 0.3:  # equal factors everywhere: symmetric patterns, minimal cases
            fs = [fs[0]] * 6
        print(domain, spacing, winding, mode, *fs)


if __name__ == "__main__":
    main()
