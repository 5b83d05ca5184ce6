#!/usr/bin/python3
"""Writes meshes/counter.stl (binary STL): a kitchen counter with a sink.

Usage: scripts/make_counter_mesh.py [OUTPUT_FILE]   (default: the package's meshes/counter.stl)

A 1.2 x 0.6 x 0.04 m slab whose origin is the centre of its top face (top at z = 0, x in
[-0.6, 0.6], y in [-0.3, 0.3]), with a 0.4 x 0.3 m sink opening through it (x in [0.1, 0.5],
y in [-0.15, 0.15]) and a basin below the opening: 0.01 m thick walls, the basin floor's top at
z = -0.18, its underside at z = -0.19. One closed surface, triangles counter-clockwise seen
from outside (outward normals), 44 triangles.
Support surfaces: the counter top around the opening (0.72 - 0.12 = 0.60 m^2, the opening a
hole of 0.12 m^2) at z = 0, and the basin floor (0.12 m^2) at z = -0.18.
"""
import os
import sys

import numpy as np

TOP, BOTTOM = 0.0, -0.04
FLOOR, UNDERSIDE = -0.18, -0.19
OUTER = [(-0.6, -0.3), (0.6, -0.3), (0.6, 0.3), (-0.6, 0.3)]
SINK = [(0.1, -0.15), (0.5, -0.15), (0.5, 0.15), (0.1, 0.15)]
WALL = 0.01
BASIN = [(0.1 - WALL, -0.15 - WALL), (0.5 + WALL, -0.15 - WALL), (0.5 + WALL, 0.15 + WALL),
         (0.1 - WALL, 0.15 + WALL)]


def at(ring, z):
    return [(x, y, z) for x, y in ring]


def ring_between(outer, inner):
    """Up-facing triangles of the region between two counter-clockwise rectangles (corners
    matching), as four trapezoids."""
    tris = []
    for k in range(4):
        j = (k + 1) % 4
        tris.append((outer[k], outer[j], inner[j]))
        tris.append((outer[k], inner[j], inner[k]))
    return tris


def walls(ring, z_low, z_high):
    """Vertical walls along a counter-clockwise ring, facing out of it."""
    low, high = at(ring, z_low), at(ring, z_high)
    tris = []
    for k in range(4):
        j = (k + 1) % 4
        tris.append((low[k], low[j], high[j]))
        tris.append((low[k], high[j], high[k]))
    return tris


def flipped(tris):
    return [(a, c, b) for a, b, c in tris]


def rectangle(ring, z):
    a, b, c, d = at(ring, z)
    return [(a, b, c), (a, c, d)]


def counter():
    tris = []
    tris += ring_between(at(OUTER, TOP), at(SINK, TOP))          # counter top, up
    tris += flipped(walls(SINK, FLOOR, TOP))                      # sink's inner walls, inward
    tris += rectangle(SINK, FLOOR)                                # basin floor, up
    tris += walls(BASIN, UNDERSIDE, BOTTOM)                       # basin's outer walls
    tris += flipped(rectangle(BASIN, UNDERSIDE))                  # basin underside, down
    tris += flipped(ring_between(at(OUTER, BOTTOM), at(BASIN, BOTTOM)))  # slab underside, down
    tris += walls(OUTER, BOTTOM, TOP)                             # slab edges
    return np.array(tris, dtype=np.float64)


def write_binary_stl(path, tris):
    normals = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    record = np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])
    data = np.zeros(len(tris), dtype=record)
    data["normal"] = normals
    data["vertices"] = tris
    with open(path, "wb") as f:
        f.write(b"counter with a sink, placement_samplers".ljust(80, b" "))
        f.write(np.uint32(len(tris)).tobytes())
        f.write(data.tobytes())


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "meshes", "counter.stl")
    tris = counter()
    # Closed with consistent winding: every directed edge is met once in each direction.
    edges = {}
    for t in tris:
        for k in range(3):
            e = (tuple(t[k]), tuple(t[(k + 1) % 3]))
            edges[e] = edges.get(e, 0) + 1
    assert all(edges.get((b, a)) == 1 and n == 1 for (a, b), n in edges.items()), "not closed"
    write_binary_stl(out, tris)


if __name__ == "__main__":
    main()
