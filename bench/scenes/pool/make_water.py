#!/usr/bin/env python3
"""Writes water.obj: the pool's water surface, a height field of three sine waves over
[-2, 2] x [-2, 2] at height 1, with normals from the waves' own derivatives (smooth shading),
facing up (the air side). Usage: python3 make_water.py [N] (N x N quads, default 64)."""
import math
import sys

N = int(sys.argv[1]) if len(sys.argv) > 1 else 64
WAVES = [  # amplitude, kx, kz, phase
    (0.020, 3.1, 0.7, 0.0),
    (0.015, -1.3, 2.3, 1.0),
    (0.010, 5.3, 4.1, 2.0),
]


def height(x, z):
    return 1.0 + sum(a * math.sin(kx * x + kz * z + p) for a, kx, kz, p in WAVES)


def normal(x, z):
    dx = sum(a * kx * math.cos(kx * x + kz * z + p) for a, kx, kz, p in WAVES)
    dz = sum(a * kz * math.cos(kx * x + kz * z + p) for a, kx, kz, p in WAVES)
    n = (-dx, 1.0, -dz)
    length = math.sqrt(sum(c * c for c in n))
    return tuple(c / length for c in n)


with open("water.obj", "w") as out:
    out.write("# The pool's water surface (make_water.py %d)\n" % N)
    for i in range(N + 1):
        for j in range(N + 1):
            x, z = -2 + 4 * j / N, -2 + 4 * i / N
            out.write("v %.6f %.6f %.6f\n" % (x, height(x, z), z))
    for i in range(N + 1):
        for j in range(N + 1):
            x, z = -2 + 4 * j / N, -2 + 4 * i / N
            out.write("vn %.6f %.6f %.6f\n" % normal(x, z))
    for i in range(N):
        for j in range(N):
            a = i * (N + 1) + j + 1
            b, c, d = a + 1, a + N + 1, a + N + 2
            # Counter-clockwise seen from above (+y), so the face normals point up like the vertex normals.
            out.write("f %d//%d %d//%d %d//%d\n" % (a, a, c, c, b, b))
            out.write("f %d//%d %d//%d %d//%d\n" % (b, b, c, c, d, d))
