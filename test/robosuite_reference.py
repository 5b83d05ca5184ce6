#!/usr/bin/env python3
"""Whole scenes of sample_scenes against robosuite's own sampling loop.

The classes below re-state robosuite's UniformRandomSampler and SequentialCompositeSampler
(robosuite/utils/placement_samplers.py) as they sample: for each object, up to max_attempts
times, x then y from rng.uniform after the boundary shrink, z from the reference and the
offsets, the radius + height test against every placed object and fixture; after the accepted
attempt the rotation (rng.uniform(0, 2 pi) when omitted, rng.uniform(min, max) for a pair,
nothing for a fixed angle). Every sub-sampler of scene i of seed S gets the same
rng = numpy.random.default_rng([S, i]); the hidden objects' sampler gets
default_rng(SeedSequence([S, i]).spawn(1)[0]). A scene fails when robosuite would raise.

The samplers are built from `sample_scenes --describe` (the sampler tree, the fixtures' poses,
the radii and offsets of objects robosuite has no class for) and, for the configuration's boxes,
cylinders, spheres and capsules (upright or turned about z, no given offsets), from robosuite's
own primitive objects of the configured sizes, their numbers computed here in numpy (and each
must equal what --describe says, bit for bit); the scenes are compared with `sample_scenes --seed S --first-scene N
--scenes K`: positions bit for bit, attempts, sampler names, success, orientations within
1e-12 (robosuite's quaternion for objects without an init_orientation; for the others the
library's documented convention R_axis(angle) * init, see README).

    test/robosuite_reference.py --sample-scenes PROGRAM --config FILE [--seed S ...]
        [--first-scene N ...] [--scenes K] [--expect-failures]

Exit status 0 when every scene matches (and, with --expect-failures, some scene failed).
"""

import argparse
import collections.abc
import json
import subprocess
import sys

import numpy as np
import yaml


class RandomizationError(Exception):
    pass


class MujocoObjectStandIn:
    """What robosuite's samplers read of a MujocoObject."""

    def __init__(self, name, values):
        self.name = name
        self.horizontal_radius = values["horizontal_radius"]
        self.bottom_offset = np.array(values["bottom_offset"])
        self.top_offset = np.array(values["top_offset"])
        x, y, z, w = values.get("init_orientation", [0.0, 0.0, 0.0, 1.0])
        self.init_xyzw = (x, y, z, w)


def robosuite_numbers(kind, size):
    """(horizontal_radius, bottom_offset, top_offset) of robosuite's BoxObject, CylinderObject,
    BallObject or CapsuleObject (robosuite/models/objects/primitive/) of `size`: half sizes,
    (radius, half length), (radius,), (radius, half length)."""
    size = np.array(size)
    if kind == "box":
        return (np.linalg.norm(size[0:2], 2), np.array([0, 0, -1 * size[2]]),
                np.array([0, 0, size[2]]))
    if kind == "cylinder":
        return size[0], np.array([0, 0, -1 * size[1]]), np.array([0, 0, size[1]])
    if kind == "sphere":
        return size[0], np.array([0, 0, -1 * size[0]]), np.array([0, 0, size[0]])
    return (size[0], np.array([0, 0, -1 * (size[0] + size[1])]),
            np.array([0, 0, (size[0] + size[1])]))


def keeps_z_vertical(xyzw):
    """An orientation that turns about z (or turns upside down): robosuite's numbers hold."""
    x, y, z, w = xyzw
    return (x, y) == (0, 0) or (z, w) == (0, 0)


def primitive_object(name, entry, orientation=None):
    """robosuite's primitive object for a configured one (its sizes as robosuite takes them),
    or None when the object is not one: a mesh, composite, URDF or MJCF object, given offsets,
    or turned so that robosuite's numbers would not bound it."""
    if not isinstance(entry, dict) or entry.get("shape") not in ("box", "cylinder", "sphere",
                                                                 "capsule"):
        return None
    if any(k in entry for k in ("horizontal_radius", "bottom_offset", "top_offset")):
        return None
    for q in (entry.get("init_orientation"), orientation):
        if q is not None and not keeps_z_vertical(q):
            return None
    kind = entry["shape"]
    if kind == "box":
        size = [0.5 * float(v) for v in entry["size"]]
    elif kind == "sphere":
        size = [float(entry["radius"])]
    else:
        size = [float(entry["radius"]), 0.5 * float(entry["length"])]
    radius, bottom, top = robosuite_numbers(kind, size)
    x, y, z, w = entry.get("init_orientation", [0.0, 0.0, 0.0, 1.0])
    return MujocoObjectStandIn(name, {"horizontal_radius": radius, "bottom_offset": bottom,
                                      "top_offset": top, "init_orientation": [x, y, z, w]})


def same_numbers(a, b):
    return ([float(a.horizontal_radius)] + [float(v) for v in a.bottom_offset] +
            [float(v) for v in a.top_offset]) == ([float(b.horizontal_radius)] +
                                                  [float(v) for v in b.bottom_offset] +
                                                  [float(v) for v in b.top_offset])


def robosuite_objects(description, config):
    """The objects and fixtures robosuite's samplers get: robosuite's own primitive objects for
    the configuration's primitives (their numbers computed here, in numpy, from the sizes),
    `--describe`'s numbers for the others. Also every primitive whose described numbers are not
    robosuite's."""
    configured = config.get("objects") or {}
    objects = {}
    problems = []
    for name, values in description["objects"].items():
        described = MujocoObjectStandIn(name, values)
        own = primitive_object(name, configured.get(name))
        if own is not None and not same_numbers(own, described):
            problems.append("object %s: described radius %r, bottom %r, top %r; robosuite's %r, "
                            "%r, %r" % (name, described.horizontal_radius,
                                        list(described.bottom_offset), list(described.top_offset),
                                        own.horizontal_radius, list(own.bottom_offset),
                                        list(own.top_offset)))
        objects[name] = own or described
    configured_fixtures = {g.get("name"): g for g in config.get("fixtures") or []}
    fixtures = collections.OrderedDict()
    for f in description["fixtures"]:
        described = MujocoObjectStandIn(f["name"], f)
        g = configured_fixtures.get(f["name"])
        own = g and primitive_object(f["name"], configured.get(g.get("object")), f["orientation"])
        if own is not None and not same_numbers(own, described):
            problems.append("fixture %s: described radius %r; robosuite's %r" % (
                f["name"], described.horizontal_radius, own.horizontal_radius))
        fixtures[f["name"]] = (tuple(f["position"]), None, own or described)
    return objects, fixtures, problems


class UniformRandomSampler:
    def __init__(self, name, mujoco_objects, x_range, y_range, rotation, rotation_axis,
                 ensure_object_boundary_in_range, ensure_valid_placement, reference_pos,
                 z_offset, rng, max_attempts):
        self.name = name
        self.mujoco_objects = mujoco_objects
        self.x_range = x_range
        self.y_range = y_range
        self.rotation = rotation
        self.rotation_axis = rotation_axis
        self.ensure_object_boundary_in_range = ensure_object_boundary_in_range
        self.ensure_valid_placement = ensure_valid_placement
        self.reference_pos = reference_pos
        self.z_offset = z_offset
        self.rng = rng
        self.max_attempts = max_attempts  # robosuite: range(5000)

    def _sample_x(self, object_horizontal_radius):
        minimum, maximum = self.x_range
        if self.ensure_object_boundary_in_range:
            minimum += object_horizontal_radius
            maximum -= object_horizontal_radius
        return self.rng.uniform(high=maximum, low=minimum)

    def _sample_y(self, object_horizontal_radius):
        minimum, maximum = self.y_range
        if self.ensure_object_boundary_in_range:
            minimum += object_horizontal_radius
            maximum -= object_horizontal_radius
        return self.rng.uniform(high=maximum, low=minimum)

    def _sample_angle(self):
        if self.rotation is None:
            return self.rng.uniform(high=2 * np.pi, low=0)
        if isinstance(self.rotation, collections.abc.Iterable):
            return self.rng.uniform(high=max(self.rotation), low=min(self.rotation))
        return self.rotation

    def sample(self, fixtures, reference, on_top, log):
        placed_objects = dict(fixtures)
        if reference is None:
            base_offset = self.reference_pos
        elif isinstance(reference, str):
            assert reference in placed_objects, reference
            ref_pos, _, ref_obj = placed_objects[reference]
            base_offset = np.array(ref_pos)
            if on_top:
                base_offset += np.array((0, 0, ref_obj.top_offset[-1]))
        else:
            base_offset = np.array(reference)
        for obj in self.mujoco_objects:
            assert obj.name not in placed_objects
            horizontal_radius = obj.horizontal_radius
            bottom_offset = obj.bottom_offset
            success = False
            for i in range(self.max_attempts):
                object_x = self._sample_x(horizontal_radius) + base_offset[0]
                object_y = self._sample_y(horizontal_radius) + base_offset[1]
                object_z = self.z_offset + base_offset[2]
                if on_top:
                    object_z -= bottom_offset[-1]
                location_valid = True
                if self.ensure_valid_placement:
                    for (x, y, z), _, other_obj in placed_objects.values():
                        if (np.linalg.norm((object_x - x, object_y - y)) <=
                                other_obj.horizontal_radius + horizontal_radius) and (
                                    object_z - z <= other_obj.top_offset[-1] - bottom_offset[-1]):
                            location_valid = False
                            break
                if location_valid:
                    angle = self._sample_angle()
                    pos = (object_x, object_y, object_z)
                    placed_objects[obj.name] = (pos, angle, obj)
                    log.append((obj.name, self.name, pos, angle, self.rotation_axis, obj, i + 1))
                    success = True
                    break
            if not success:
                raise RandomizationError("Cannot place all objects ):")
        return placed_objects


class SequentialCompositeSampler:
    def __init__(self, name):
        self.name = name
        self.samplers = collections.OrderedDict()
        self.sample_args = collections.OrderedDict()

    def append_sampler(self, sampler, sample_args=None):
        self.samplers[sampler.name] = sampler
        self.sample_args[sampler.name] = sample_args

    def sample(self, fixtures, reference, on_top, log):
        placed_objects = dict(fixtures)
        for sampler, s_args in zip(self.samplers.values(), self.sample_args.values()):
            # A copy: robosuite writes the call's values into the stored dict (a known quirk
            # the library does not have); every call here gives the same values anyway.
            s_args = dict(s_args or {})
            for arg_name, arg in zip(("reference", "on_top"), (reference, on_top)):
                if arg_name not in s_args:
                    s_args[arg_name] = arg
            placed_objects.update(sampler.sample(placed_objects, log=log, **s_args))
        return placed_objects


def build(node, objects, rng, hidden_rng):
    if node["type"] == "uniform":
        rotation = node["rotation"]
        if isinstance(rotation, list):
            rotation = tuple(rotation)
        return UniformRandomSampler(
            name=node["name"], mujoco_objects=[objects[n] for n in node["objects"]],
            x_range=tuple(node["x_range"]), y_range=tuple(node["y_range"]), rotation=rotation,
            rotation_axis=node["rotation_axis"],
            ensure_object_boundary_in_range=node["ensure_object_boundary_in_range"],
            ensure_valid_placement=node["ensure_valid_placement"],
            reference_pos=np.array(node["reference_pos"]), z_offset=node["z_offset"],
            rng=hidden_rng if node["hides"] else rng, max_attempts=node["max_attempts"])
    composite = SequentialCompositeSampler(node["name"])
    for child in node["samplers"]:
        args = dict(child["sample_args"])
        if isinstance(args.get("reference"), list):
            args["reference"] = tuple(args["reference"])
        composite.append_sampler(build(child["sampler"], objects, rng, hidden_rng), args or None)
    return composite


def quat_mul_wxyz(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw)


def expected_orientation_xyzw(angle, axis, obj):
    # robosuite's _sample_quat, (w, x, y, z).
    c, s = np.cos(angle / 2), np.sin(angle / 2)
    quat = {"x": (c, s, 0, 0), "y": (c, 0, s, 0), "z": (c, 0, 0, s)}[axis]
    x, y, z, w = obj.init_xyzw
    if (x, y, z, w) != (0.0, 0.0, 0.0, 1.0):
        # robosuite composes these in float32 with mixed conventions; the library's is
        # R_axis(angle) * init (README, "robosuite semantics").
        quat = quat_mul_wxyz(quat, (w, x, y, z))
    return (quat[1], quat[2], quat[3], quat[0])


def reference_scene(description, objects, fixtures, seed, index):
    fixtures = collections.OrderedDict(fixtures)
    rng = np.random.default_rng([seed, index])
    hidden_rng = np.random.default_rng(np.random.SeedSequence([seed, index]).spawn(1)[0])
    root = build(description["sampler"], objects, rng, hidden_rng)
    log = []
    try:
        root.sample(fixtures, reference=None, on_top=True, log=log)
        success = True
    except RandomizationError:
        success = False
    return success, log


def compare(description, objects, fixtures, scene):
    success, log = reference_scene(description, objects, fixtures, scene["seed"], scene["scene"])
    where = "seed %d scene %d" % (scene["seed"], scene["scene"])
    problems = []
    if success != scene["success"]:
        problems.append("%s: robosuite %s, sample_scenes %s (%s)" % (
            where, "placed it" if success else "raised", "placed it" if scene["success"] else
            "failed", scene["message"]))
    ours = scene["placements"]
    if len(ours) != len(log):
        problems.append("%s: %d placements, robosuite %d" % (where, len(ours), len(log)))
    for p, (name, sampler, pos, angle, axis, obj, attempts) in zip(ours, log):
        if (p["name"], p["sampler"], p["attempts"]) != (name, sampler, attempts):
            problems.append("%s: %s by %s in %d attempts, robosuite %s by %s in %d" % (
                where, p["name"], p["sampler"], p["attempts"], name, sampler, attempts))
        if [float(v) for v in p["position"]] != [float(v) for v in pos]:
            problems.append("%s: %s at %r, robosuite %r" % (where, name, p["position"], pos))
        expected = expected_orientation_xyzw(angle, axis, obj)
        if max(abs(a - b) for a, b in zip(p["orientation"], expected)) > 1e-12:
            problems.append("%s: %s orientation %r, robosuite %r" % (
                where, name, p["orientation"], expected))
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sample-scenes", required=True, help="the sample_scenes program")
    parser.add_argument("--config", required=True)
    parser.add_argument("--seed", type=int, action="append", required=True)
    parser.add_argument("--first-scene", type=int, action="append",
                        help="first scene index of a run (repeatable; default 0)")
    parser.add_argument("--scenes", type=int, default=20, help="scenes per seed and first scene")
    parser.add_argument("--expect-failures", action="store_true",
                        help="some scene must fail (the configuration is meant to)")
    args = parser.parse_args()
    firsts = args.first_scene or [0]

    description = json.loads(subprocess.run(
        [args.sample_scenes, "--config", args.config, "--describe"], check=True,
        stdout=subprocess.PIPE, universal_newlines=True).stdout)
    with open(args.config) as f:
        config = yaml.safe_load(f) or {}
    objects, fixtures, problems = robosuite_objects(description, config)
    failures = 0
    total = 0
    for seed, first in [(s, f) for s in args.seed for f in firsts]:
        run = subprocess.run(
            [args.sample_scenes, "--config", args.config, "--seed", str(seed), "--first-scene",
             str(first), "--scenes", str(args.scenes), "--threads", "1"],
            stdout=subprocess.PIPE, universal_newlines=True)
        if run.returncode not in (0, 1):
            print("sample_scenes exited with %d" % run.returncode)
            return 1
        for line in run.stdout.splitlines():
            scene = json.loads(line)
            total += 1
            failures += 0 if scene["success"] else 1
            problems += compare(description, objects, fixtures, scene)
    for p in problems[:20]:
        print(p)
    print("%s: %d scenes (%d failed), %d differences from robosuite's loop" % (
        args.config, total, failures, len(problems)))
    if total != args.scenes * len(args.seed) * len(firsts):
        print("expected %d scenes" % (args.scenes * len(args.seed) * len(firsts)))
        return 1
    if args.expect_failures and failures == 0:
        print("no scene failed, but the configuration is meant to make some fail")
        return 1
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
