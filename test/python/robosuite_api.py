"""robosuite's sampler API around what the tests and benchmarks compare with: stand-ins for the
few robosuite modules robosuite's placement_samplers.py imports, robosuite's own file loaded
from the path in ROBOSUITE_PLACEMENT_SAMPLERS (never part of this repository), and
test/robosuite_reference.py behind an adapter with robosuite's API.

Import it before placement_samplers.robosuite: the module takes robosuite's RandomizationError
(here the stand-in's) when robosuite is imported first.
"""

import collections
import copy
import importlib.util
import os
import sys
import types

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))

import robosuite_reference  # noqa: E402
import robosuite_setups  # noqa: E402


# ---- Stand-ins for what robosuite's placement_samplers.py imports ----
class RandomizationError(Exception):
    """robosuite.utils.RandomizationError."""


def quat_multiply(quaternion1, quaternion0):
    """robosuite.utils.transform_utils.quat_multiply: the product q1 * q0 of two (x, y, z, w)
    quaternions, its terms added in robosuite's order, as float32."""
    x0, y0, z0, w0 = quaternion0
    x1, y1, z1, w1 = quaternion1
    x = x1 * w0 + y1 * z0 - z1 * y0 + w1 * x0
    y = -x1 * z0 + y1 * w0 + z1 * x0 + w1 * y0
    z = x1 * y0 - y1 * x0 + z1 * w0 + w1 * z0
    w = -x1 * x0 - y1 * y0 - z1 * z0 + w1 * w0
    return np.array((x, y, z, w), dtype=np.float32)


def install_stand_ins():
    modules = {name: types.ModuleType(name) for name in (
        "robosuite", "robosuite.models", "robosuite.models.objects", "robosuite.utils",
        "robosuite.utils.transform_utils")}
    modules["robosuite.models.objects"].MujocoObject = robosuite_setups.MujocoObject
    modules["robosuite.utils"].RandomizationError = RandomizationError
    modules["robosuite.utils.transform_utils"].quat_multiply = quat_multiply
    sys.modules.update(modules)


install_stand_ins()


# ---- test/robosuite_reference.py behind robosuite's API ----
class ReferenceUniform:
    """robosuite's UniformRandomSampler API on robosuite_reference.UniformRandomSampler."""

    def __init__(self, name, mujoco_objects=None, x_range=(0, 0), y_range=(0, 0), rotation=None,
                 rotation_axis="z", ensure_object_boundary_in_range=True,
                 ensure_valid_placement=True, reference_pos=(0, 0, 0), z_offset=0.0, rng=None):
        self.name = name
        if mujoco_objects is None:
            mujoco_objects = []
        elif isinstance(mujoco_objects, robosuite_setups.MujocoObject):
            mujoco_objects = [mujoco_objects]
        self.mujoco_objects = list(mujoco_objects)
        self.args = dict(x_range=x_range, y_range=y_range, rotation=rotation,
                         rotation_axis=rotation_axis, reference_pos=reference_pos,
                         ensure_object_boundary_in_range=ensure_object_boundary_in_range,
                         ensure_valid_placement=ensure_valid_placement, z_offset=z_offset)
        self.rng = rng

    def add_objects(self, mujoco_objects):
        if isinstance(mujoco_objects, robosuite_setups.MujocoObject):
            mujoco_objects = [mujoco_objects]
        self.mujoco_objects.extend(mujoco_objects)

    def sample(self, fixtures=None, reference=None, on_top=True):
        placed = copy.copy(fixtures) if fixtures is not None else {}
        inner = robosuite_reference.UniformRandomSampler(
            name=self.name, mujoco_objects=self.mujoco_objects, rng=self.rng, max_attempts=5000,
            **self.args)
        log = []
        try:
            inner.sample(placed, reference, on_top, log)
        except robosuite_reference.RandomizationError as e:
            raise RandomizationError("Cannot place all objects ):") from e
        for name, _, pos, angle, axis, obj, _ in log:
            # robosuite's _sample_quat, then quat_multiply with init_quat.
            c, s = np.cos(angle / 2), np.sin(angle / 2)
            quat = {"x": np.array([c, s, 0, 0]), "y": np.array([c, 0, s, 0]),
                    "z": np.array([c, 0, 0, s])}[axis]
            if hasattr(obj, "init_quat"):
                quat = quat_multiply(quat, obj.init_quat)
            placed[name] = (pos, quat, obj)
        return placed


class ReferenceComposite:
    """robosuite's SequentialCompositeSampler API over ReferenceUniform samplers."""

    def __init__(self, name):
        self.name = name
        self.samplers = collections.OrderedDict()
        self.sample_args = collections.OrderedDict()

    def append_sampler(self, sampler, sample_args=None):
        self.samplers[sampler.name] = sampler
        self.sample_args[sampler.name] = sample_args

    def add_objects_to_sampler(self, sampler_name, mujoco_objects):
        self.samplers[sampler_name].add_objects(mujoco_objects)

    def sample(self, fixtures=None, reference=None, on_top=True):
        placed = copy.copy(fixtures) if fixtures is not None else {}
        for sampler, args in zip(self.samplers.values(), self.sample_args.values()):
            args = dict(args or {})
            args.setdefault("reference", reference)
            args.setdefault("on_top", on_top)
            placed.update(sampler.sample(fixtures=placed, **args))
        return placed


REFERENCE = types.SimpleNamespace(UniformRandomSampler=ReferenceUniform,
                                  SequentialCompositeSampler=ReferenceComposite)


def load_robosuite():
    """robosuite's placement_samplers.py from ROBOSUITE_PLACEMENT_SAMPLERS, or None."""
    path = os.environ.get("ROBOSUITE_PLACEMENT_SAMPLERS")
    if not path:
        return None
    spec = importlib.util.spec_from_file_location("robosuite_placement_samplers", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
