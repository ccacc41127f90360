#!/usr/bin/env python3
"""Writes the quad-grid torus of osd_cull::scene::torus(N, N, 1.0, 0.4) as an OBJ file (same
vertex order and winding), for `osd-cull verify` at a million patches:

  scripts/torus_obj.py 1000 /tmp/torus1000.obj   # 1,000,000 faces, about 93 MB
"""
import math
import sys


def main(n, path):
    major, minor = 1.0, 0.4
    with open(path, "w", encoding="ascii") as f:
        f.write("# quad-grid torus %dx%d (osd_cull scene::torus layout)\n" % (n, n))
        for i in range(n):
            phi = 2 * math.pi * i / n
            for j in range(n):
                theta = 2 * math.pi * j / n
                ring = major + minor * math.cos(theta)
                f.write("v %.17g %.17g %.17g\n" % (ring * math.cos(phi), ring * math.sin(phi),
                                                   minor * math.sin(theta)))

        def at(i, j):
            return (i % n) * n + (j % n) + 1

        for i in range(n):
            for j in range(n):
                f.write("f %d %d %d %d\n" % (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(int(sys.argv[1]), sys.argv[2])
