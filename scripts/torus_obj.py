#!/usr/bin/env python3
"""Writes the quad-grid torus of osd_cull::scene::torus(N, N, 1.0, 0.4) as an OBJ file (same
vertex order and winding), for `osd-cull verify` at a million patches:

  scripts/torus_obj.py 1000 /tmp/torus1000.obj        # 1,000,000 faces, about 93 MB
  scripts/torus_obj.py 300 /tmp/torus300uv.obj --uv   # with texture coordinates (u, v) =
                                                      # (i / N, j / N), seams at 0 and 1,
                                                      # for --displacement
"""
import math
import sys


def main(n, path, uv):
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
        if uv:
            for i in range(n + 1):
                for j in range(n + 1):
                    f.write("vt %.17g %.17g\n" % (i / n, j / n))

        def at(i, j):
            return (i % n) * n + (j % n) + 1

        def corner(i, j):
            return "%d/%d" % (at(i, j), i * (n + 1) + j + 1) if uv else "%d" % at(i, j)

        for i in range(n):
            for j in range(n):
                f.write("f %s %s %s %s\n" % (corner(i, j), corner(i + 1, j), corner(i + 1, j + 1),
                                             corner(i, j + 1)))


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--uv"]
    if len(args) != 2:
        sys.exit(__doc__)
    main(int(args[0]), args[1], "--uv" in sys.argv[1:])
