#!/usr/bin/env python3
"""The derived numbers of primitive objects against robosuite's primitive objects, in numpy.

robosuite's BoxObject, CylinderObject, BallObject and CapsuleObject
(robosuite/models/objects/primitive/) give, for their size (half sizes, radius, half length):
bottom_offset [0, 0, -size[2]] / [0, 0, -size[1]] / [0, 0, -size[0]] / [0, 0, -(size[0] +
size[1])], top_offset its negation, and horizontal_radius np.linalg.norm(size[0:2], 2) for a box,
size[0] for the others. Those numbers decide robosuite's boundary shrink and overlap test, so
`sample_scenes --describe` must print exactly them (bit for bit) for primitives that stand
upright, turned about z (init_orientation or a fixture's orientation) or upside down, whose
value robosuite's number does not depend on.

Random sizes (uniform doubles, sizes rounded to millimetres as configurations write them, and
sizes over several decades), a few thousand of each kind, in configurations of at most 1000
objects (the configuration file limit), each object's description compared with numpy's.

    test/robosuite_primitives.py --sample-scenes PROGRAM [--count N] [--seed S]

Exit status 0 when every number is numpy's.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

from robosuite_reference import robosuite_numbers

KINDS = ("box", "cylinder", "sphere", "capsule")
SIZES = {"box": 3, "cylinder": 2, "sphere": 1, "capsule": 2}
BATCH = 1000


def config_entry(kind, size):
    """The configuration's sizes for robosuite's `size`: full sizes and lengths (exact: * 2)."""
    if kind == "box":
        return {"shape": "box", "size": [2 * s for s in size]}
    if kind == "sphere":
        return {"shape": "sphere", "radius": size[0]}
    return {"shape": kind, "radius": size[0], "length": 2 * size[1]}


def random_size(rng, kind, style):
    n = SIZES[kind]
    if style == 0:
        values = rng.uniform(0.001, 0.5, n)
    elif style == 1:
        values = np.round(rng.uniform(0.001, 0.5, n), 3)
    else:
        values = 10.0 ** rng.uniform(-4, 2, n)
    return [float(v) for v in np.maximum(values, 1e-4)]


def random_turn(rng, style):
    """An orientation [x, y, z, w] that keeps the z axis vertical, or None."""
    if style == 0:
        return None
    if style == 1:
        angle = rng.uniform(-2 * np.pi, 2 * np.pi)
        return [0.0, 0.0, float(np.sin(angle / 2)), float(np.cos(angle / 2))]
    if style == 2:
        return [1.0, 0.0, 0.0, 0.0]  # upside down
    return [0.0, 0.0, 1.0, 0.0]  # half a turn


def describe(program, objects, fixtures):
    lines = ["objects:"]
    for name, entry in objects:
        lines.append("  %s: %s" % (name, json.dumps(entry)))
    lines.append("fixtures:")
    for fixture in fixtures:
        lines.append("  - %s" % json.dumps(fixture))
    # One sampler: a configuration needs one; the objects are only described.
    lines.append("samplers:\n  - {name: S, objects: [%s], ensure_object_boundary_in_range: false}"
                 % objects[0][0])
    with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as f:
        f.write("\n".join(lines) + "\n")
        path = f.name
    try:
        run = subprocess.run([program, "--config", path, "--describe"], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, universal_newlines=True)
    finally:
        os.unlink(path)
    if run.returncode != 0:
        raise RuntimeError("sample_scenes --describe failed: " + run.stderr)
    return json.loads(run.stdout)


def compare(label, kind, size, turn, got):
    radius, bottom, top = robosuite_numbers(kind, size)
    want = [float(radius)] + [float(v) for v in bottom] + [float(v) for v in top]
    have = [float(v) for v in [got["horizontal_radius"]] + got["bottom_offset"] + got["top_offset"]]
    if have == want:
        return None
    return "%s: %s of size %r turned %r: got radius, bottom, top %r, numpy %r" % (
        label, kind, size, turn, have, want)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sample-scenes", required=True, help="the sample_scenes program")
    parser.add_argument("--count", type=int, default=3000, help="objects of each kind")
    parser.add_argument("--seed", type=int, default=20240607)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    problems = []
    checked = 0
    for kind in KINDS:
        done = 0
        while done < args.count:
            batch = min(BATCH, args.count - done)
            cases = []
            for i in range(batch):
                k = done + i
                cases.append(("%s%d" % (kind, k), random_size(rng, kind, k % 3),
                              random_turn(rng, k % 4)))
            objects = []
            for name, size, turn in cases:
                entry = config_entry(kind, size)
                if turn is not None:
                    entry["init_orientation"] = turn
                objects.append((name, entry))
            # Fixtures of the unturned objects at a turned pose: bounds under that pose.
            fixtures = []
            for name, size, turn in cases[:100]:
                orientation = random_turn(rng, 1 + len(fixtures) % 3)
                if turn is None:
                    fixtures.append({"name": "f_" + name, "object": name,
                                     "position": [0.0, 0.0, 0.5], "orientation": orientation})
            description = describe(args.sample_scenes, objects, fixtures)
            for name, size, turn in cases:
                p = compare(name, kind, size, turn, description["objects"][name])
                checked += 1
                if p:
                    problems.append(p)
            by_name = {name: (size, turn) for name, size, turn in cases}
            for f in description["fixtures"]:
                size, _ = by_name[f["name"][2:]]
                p = compare(f["name"], kind, size, f["orientation"], f)
                checked += 1
                if p:
                    problems.append(p)
            done += batch
    for p in problems[:20]:
        print(p)
    print("%d primitive objects and fixtures, %d differ from numpy's robosuite numbers" % (
        checked, len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
