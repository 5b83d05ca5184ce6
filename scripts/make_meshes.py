#!/usr/bin/python3
"""Writes the example meshes in meshes/ as ASCII STL: prisms extruded along z from a polygon.

Usage: scripts/make_meshes.py [OUTPUT_DIR]   (default: the package's meshes/ directory)

Each mesh is a closed surface with outward normals, centred on z = 0; sizes in metres.
"""
import os
import sys


def prism(polygon, caps, z0, z1):
    """Triangles of a prism: @polygon counter-clockwise seen from +z, @caps its triangulation
    as index triples, between heights z0 < z1."""
    bottom = [(x, y, z0) for x, y in polygon]
    top = [(x, y, z1) for x, y in polygon]
    tris = []
    for a, b, c in caps:
        tris.append((top[a], top[b], top[c]))
        tris.append((bottom[a], bottom[c], bottom[b]))
    n = len(polygon)
    for i in range(n):
        j = (i + 1) % n
        tris.append((bottom[i], bottom[j], top[j]))
        tris.append((bottom[i], top[j], top[i]))
    return tris


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    ux, uy, uz = bx - ax, by - ay, bz - az
    vx, vy, vz = cx - ax, cy - ay, cz - az
    n = (uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx)
    length = sum(c * c for c in n) ** 0.5
    return tuple(c / length for c in n)


def write_stl(path, name, tris):
    with open(path, "w") as f:
        f.write("solid %s\n" % name)
        for t in tris:
            f.write("  facet normal %g %g %g\n    outer loop\n" % normal(t))
            for v in t:
                f.write("      vertex %g %g %g\n" % v)
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid %s\n" % name)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "meshes")
    os.makedirs(out, exist_ok=True)
    # L-shaped block: a 0.08 x 0.08 footprint with 0.02 wide arms along -y and -x, 0.03 high.
    # Not convex: two of them can nest where their circles (radius 0.0566) would not let them.
    l_shape = [(-0.04, -0.04), (0.04, -0.04), (0.04, -0.02), (-0.02, -0.02), (-0.02, 0.04),
               (-0.04, 0.04)]
    l_caps = [(3, 4, 5), (3, 5, 0), (3, 0, 1), (3, 1, 2)]  # a fan from the inner corner
    write_stl(os.path.join(out, "l_block.stl"), "l_block", prism(l_shape, l_caps, -0.015, 0.015))
    # Wedge: a right triangle 0.10 x 0.05 in x-y, 0.04 high.
    wedge = [(-0.05, -0.025), (0.05, -0.025), (-0.05, 0.025)]
    write_stl(os.path.join(out, "wedge.stl"), "wedge", prism(wedge, [(0, 1, 2)], -0.02, 0.02))


if __name__ == "__main__":
    main()
