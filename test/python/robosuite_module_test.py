#!/usr/bin/env python3
"""placement_samplers.robosuite against robosuite's samplers, call for call.

Each setup of robosuite_setups.py (the samplers of robosuite's Lift, Stack, PickPlace and
NutAssembly, one that fails about one call in a hundred, one with fixtures, a named reference,
rotation ranges and init_quat) is built twice, each time with a Generator of its own seeded
alike, once with this module and once with the implementation compared; then sample() is called
on both, many times: every call must give the same dict (keys in order, pos, quat bit for bit
with its dtype, the same objects) or raise the same exception, and leave both Generators in
the same state.

Implementations compared:
- test/robosuite_reference.py, the project's re-statement of robosuite's sampling loop, behind
  an adapter with robosuite's API (always);
- robosuite's own robosuite/utils/placement_samplers.py, loaded from the path in the
  environment variable ROBOSUITE_PLACEMENT_SAMPLERS (skipped, saying so, when unset). It is
  never part of this repository; its imports of robosuite are served by stand-ins below.

    robosuite_module_test.py [--calls N] [--sample-scenes PROGRAM] [unittest arguments]
"""

import collections
import os
import subprocess
import sys
import tempfile
import types
import unittest
import weakref

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))

import robosuite_setups  # noqa: E402
from robosuite_setups import SETUPS  # noqa: E402


# Before the module: it takes robosuite.utils.RandomizationError when robosuite is imported.
from robosuite_api import REFERENCE, RandomizationError, load_robosuite  # noqa: E402
import placement_samplers.robosuite as ours  # noqa: E402

CALLS = 10000


# ---- Comparing ----
def outcome(sampler, kwargs):
    try:
        return sampler.sample(**kwargs), None
    except Exception as e:  # noqa: BLE001 - the exception is what is compared
        return None, e


def describe_difference(ours_result, theirs_result):
    """Why two sample() results differ, or None."""
    (mine, my_error), (theirs, their_error) = ours_result, theirs_result
    if my_error is not None or their_error is not None:
        if my_error is None or their_error is None:
            return "one raised, the other did not: %r / %r" % (my_error, their_error)
        if (type(my_error).__name__, str(my_error)) != (type(their_error).__name__,
                                                        str(their_error)):
            return "raised %s(%r), expected %s(%r)" % (type(my_error).__name__, str(my_error),
                                                       type(their_error).__name__,
                                                       str(their_error))
        return None
    if list(mine) != list(theirs):
        return "keys %s, expected %s" % (list(mine), list(theirs))
    for name in theirs:
        (pos, quat, obj), (pos2, quat2, obj2) = mine[name], theirs[name]
        if len(pos) != 3 or [float(v) for v in pos] != [float(v) for v in pos2]:
            return "%s at %r, expected %r" % (name, pos, pos2)
        quat, quat2 = np.asarray(quat), np.asarray(quat2)
        if quat.dtype != quat2.dtype or quat.tobytes() != quat2.tobytes():
            return "%s quat %r (%s), expected %r (%s)" % (name, quat, quat.dtype, quat2,
                                                         quat2.dtype)
        if obj is not obj2:
            return "%s: another object" % name
    return None


def same_state(a, b):
    """Equal bit generator states (dicts of ints, arrays, nested dicts)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_state(a[k], b[k]) for k in a)
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(a, b)
    return a == b


class Comparison:
    """One setup built with this module and with another implementation, each with its own
    Generator seeded alike."""

    def __init__(self, setup, theirs, seed, bit_generator=np.random.PCG64, objects="plain",
                 **options):
        self.rng = np.random.Generator(bit_generator(seed))
        self.their_rng = np.random.Generator(bit_generator(seed))
        self.mine = setup(ours, self.rng, objects, **options)
        # The same objects on both sides: the results hold them.
        self.theirs = setup(theirs, self.their_rng, objects, **options)
        self.share_objects(self.mine, self.theirs)

    @staticmethod
    def share_objects(mine, theirs):
        if hasattr(theirs, "samplers"):
            for a, b in zip(mine.samplers.values(), theirs.samplers.values()):
                Comparison.share_objects(a, b)
            return
        theirs.mujoco_objects[:] = list(mine.mujoco_objects)

    def run(self, calls, **kwargs):
        """Calls sample() @p calls times on both; returns (differences, failed calls)."""
        differences = []
        failed = 0
        for call in range(calls):
            mine = outcome(self.mine, kwargs)
            theirs = outcome(self.theirs, kwargs)
            failed += theirs[1] is not None
            why = describe_difference(mine, theirs)
            if why is None and not same_state(self.rng.bit_generator.state,
                                              self.their_rng.bit_generator.state):
                why = "Generator states differ"
            if why is not None:
                differences.append("call %d: %s" % (call, why))
                if len(differences) >= 5:
                    break
        return differences, failed


class AgainstReference(unittest.TestCase):
    """The module against test/robosuite_reference.py's sampling loop."""

    theirs = REFERENCE

    def compare(self, name, calls=None, expect_failures=(0, 0), **options):
        calls = calls or CALLS
        comparison = Comparison(SETUPS[name], self.theirs, seed=20240605 + len(name), **options)
        differences, failed = comparison.run(calls)
        self.assertEqual(differences, [], name)
        low, high = expect_failures
        self.assertTrue(low <= failed <= high, "%s: %d of %d calls failed, expected %d to %d"
                        % (name, failed, calls, low, high))
        print("%s: %d calls, %d raised, same results and Generator states" % (name, calls,
                                                                               failed))

    def test_lift(self):
        self.compare("lift")

    def test_stack(self):
        self.compare("stack")

    def test_pick_place(self):
        self.compare("pick_place")

    def test_nut_assembly(self):
        self.compare("nut_assembly")

    def test_crowded_fails_alike(self):
        self.compare("crowded", expect_failures=(CALLS // 400, CALLS // 30))

    def test_nut_assembly_with_the_shrink_raises_alike(self):
        # The x range reversed by the nuts' radius: numpy's Generator refuses it.
        self.compare("nut_assembly", calls=200, expect_failures=(200, 200), shrink=True)

    def test_robosuite_like_objects(self):
        for name in ("lift", "pick_place"):
            self.compare(name, calls=CALLS // 5, objects="robosuite")

    def test_stacked_with_fixtures(self):
        comparison = Comparison(SETUPS["stacked"], self.theirs, seed=7)
        differences, failed = comparison.run(CALLS, fixtures=robosuite_setups.FIXTURES)
        self.assertEqual(differences, [])
        print("stacked: %d calls with fixtures, %d raised, same results and Generator states"
              % (CALLS, failed))

    def test_attributes_changed_between_calls(self):
        # robosuite reads the objects' attributes at every call: a change between calls (of an
        # instance attribute, of an array in place, of the class, of the object's class or
        # dict) shows in the next call.
        comparison = Comparison(SETUPS["pick_place"], self.theirs, seed=11)

        class Fresh(robosuite_setups.PlainObject):
            pass

        class Other(robosuite_setups.PlainObject):
            bottom_offset = property(lambda self: np.array([0.0, 0.0, -0.01]))
            top_offset = np.array([0.0, 0.0, 0.06])

        objects = list(comparison.mine.samplers["CollisionObjectSampler"].mujoco_objects)
        for obj in objects:
            obj.__class__ = Fresh
        milk, bread, cereal, can = objects
        steps = [
            ("radius", lambda: setattr(milk, "horizontal_radius", 0.09)),
            ("radius again", lambda: setattr(milk, "horizontal_radius", 0.025)),
            ("bottom changed in place", lambda: bread.bottom_offset.__setitem__(2, -0.3)),
            ("top", lambda: setattr(cereal, "top_offset", np.array([0.0, 0.0, 0.4]))),
            ("top changed in place", lambda: cereal.top_offset.__setitem__(2, -0.2)),
            ("init_quat added", lambda: setattr(can, "init_quat", [0.0, 0.0, 0.38, 0.92])),
            ("init_quat removed", lambda: delattr(can, "init_quat")),
            ("a property of the class", lambda: setattr(Fresh, "horizontal_radius",
                                                        property(lambda self: 0.1))),
            ("the property removed", lambda: delattr(Fresh, "horizontal_radius")),
            ("a class attribute where the instance has none",
             lambda: (delattr(bread, "top_offset"),
                      setattr(Fresh, "top_offset", np.array([0.0, 0.0, 0.35])))),
            ("the class attribute changed", lambda: setattr(Fresh, "top_offset",
                                                            np.array([0.0, 0.0, -0.1]))),
            ("another class", lambda: setattr(bread, "__class__", Other)),
            ("another dict", lambda: setattr(cereal, "__dict__",
                                             dict(cereal.__dict__, horizontal_radius=0.08))),
            ("another name", lambda: setattr(can, "name", "Tin")),
            ("a property of a base class", lambda: setattr(
                robosuite_setups.PlainObject, "bottom_offset",
                property(lambda self: np.array([0.0, 0.0, -0.15])))),
            ("the base class's property removed",
             lambda: delattr(robosuite_setups.PlainObject, "bottom_offset")),
        ]
        try:
            for label, change in steps:
                change()
                differences, _ = comparison.run(30)
                self.assertEqual(differences, [], label)
        finally:
            if "bottom_offset" in vars(robosuite_setups.PlainObject):
                del robosuite_setups.PlainObject.bottom_offset

    def test_each_result_has_arrays_of_its_own(self):
        # Quaternions kept keep their values; what a caller does to one it dropped (its values,
        # shape, flags or dtype, a weak reference to it) shows in no later result.
        comparison = Comparison(SETUPS["pick_place"], self.theirs, seed=5)
        kept, weak = [], []
        changes = [lambda q: q.__setitem__(slice(None), 7.0),
                   lambda q: setattr(q, "shape", (2, 2)),
                   lambda q: q.setflags(write=False),
                   lambda q: setattr(q, "dtype", np.int64),
                   lambda q: weak.append(weakref.ref(q))]
        for call in range(400):
            mine, theirs = outcome(comparison.mine, {}), outcome(comparison.theirs, {})
            self.assertIsNone(describe_difference(mine, theirs), "call %d" % call)
            for _, quat, _ in mine[0].values():
                self.assertEqual((quat.shape, quat.flags.writeable, quat.flags.owndata,
                                  quat.base, weakref.getweakrefcount(quat)),
                                 ((4,), True, True, None, 0), "call %d" % call)
            if call % 4 == 0:
                kept.append((mine, theirs))
            elif call % 4 == 1:
                for i, (_, quat, _) in enumerate(mine[0].values()):
                    changes[(call + i) % len(changes)](quat)
        for mine, theirs in kept:
            self.assertIsNone(describe_difference(mine, theirs))
        quats = [id(quat) for mine, _ in kept for _, quat, _ in mine[0].values()]
        self.assertEqual(len(set(quats)), len(quats))


class AgainstRobosuite(AgainstReference):
    """The module against robosuite's own placement_samplers.py."""

    @classmethod
    def setUpClass(cls):
        module = load_robosuite()
        if module is None:
            reason = ("ROBOSUITE_PLACEMENT_SAMPLERS is not set: robosuite's own "
                      "placement_samplers.py not compared")
            print("skipped: " + reason)
            raise unittest.SkipTest(reason)
        cls.theirs = module


class OtherGenerators(unittest.TestCase):
    """Generators on other bit generators and numpy's legacy RandomState: drawn through
    them, exactly as robosuite's code draws."""

    def test_other_bit_generators(self):
        for bit_generator in (np.random.MT19937, np.random.Philox, np.random.SFC64,
                              np.random.PCG64DXSM):
            for name in ("lift", "pick_place", "crowded"):
                comparison = Comparison(SETUPS[name], REFERENCE, 11, bit_generator=bit_generator)
                differences, _ = comparison.run(CALLS // 10)
                self.assertEqual(differences, [], "%s %s" % (name, bit_generator.__name__))

    def test_random_state_and_generator_subclasses(self):
        class CountingGenerator(np.random.Generator):
            """Overrides uniform(): the module must call it."""

            calls = 0

            def uniform(self, *args, **kwargs):
                CountingGenerator.calls += 1
                return super().uniform(*args, **kwargs)

        for name in ("lift", "pick_place"):
            rng = np.random.RandomState(5)
            other = np.random.RandomState(5)
            mine = SETUPS[name](ours, rng)
            theirs = SETUPS[name](REFERENCE, other)
            Comparison.share_objects(mine, theirs)
            for call in range(CALLS // 10):
                self.assertIsNone(describe_difference(outcome(mine, {}), outcome(theirs, {})))
            self.assertEqual(str(rng.get_state()), str(other.get_state()))
        rng = CountingGenerator(np.random.PCG64(3))
        SETUPS["lift"](ours, rng).sample()
        self.assertEqual(CountingGenerator.calls, 3)  # x, y, rotation

    def test_state_through_the_dict(self):
        self.assertEqual(ours._pcg64_state_access(), "memory")
        ours._set_pcg64_state_access("dict")
        try:
            self.assertEqual(ours._pcg64_state_access(), "dict")
            for name in ("lift", "pick_place"):
                differences, _ = Comparison(SETUPS[name], REFERENCE, 3).run(CALLS // 10)
                self.assertEqual(differences, [], name)
        finally:
            ours._set_pcg64_state_access("memory")
        with self.assertRaisesRegex(ValueError, "expected 'memory' or 'dict', got 'disk'"):
            ours._set_pcg64_state_access("disk")

    def test_a_draw_of_another_thread_is_waited_for(self):
        import threading
        rng = np.random.default_rng(8)
        sampler = SETUPS["lift"](ours, rng)
        holding, released = threading.Event(), []

        def hold():
            with rng.bit_generator.lock:  # as numpy holds it while it draws
                holding.set()
                threading.Event().wait(0.2)
                released.append(True)

        other = threading.Thread(target=hold)
        other.start()
        holding.wait()
        placed = sampler.sample()
        self.assertEqual(released, [True], "sample() ran while the lock was held")
        other.join()
        expected = SETUPS["lift"](REFERENCE, np.random.default_rng(8)).sample()
        self.assertEqual(placed["cube"][0], tuple(float(v) for v in expected["cube"][0]))

    def test_numpy_loops(self):
        # Quaternions come from numpy's own float64 cos and sin loops (checked at import).
        self.assertTrue(ours._numpy_loops_in_use())


def plain(name, radius=0.02, bottom=-0.02, top=0.02, **extra):
    obj = robosuite_setups.PlainObject(name, radius, bottom, top)
    for key, value in extra.items():
        setattr(obj, key, value)
    return obj


def after_draws(seed, draws):
    """A Generator seeded with @p seed after @p draws uniform draws."""
    rng = np.random.default_rng(seed)
    for _ in range(draws):
        rng.uniform()
    return rng


def casting_error():
    """The class of numpy's error for a float added in place to an integer array."""
    try:
        base = np.array((0, 0, 1))
        base += np.array((0, 0, 0.5))
    except TypeError as e:
        return type(e)
    return None


# What robosuite raises, and how many draws it makes first: (setup, sample() keyword arguments,
# exception type, message, draws from the caller's Generator before it). A setup is
# f(api, rng) -> sampler.
def uniform(**kwargs):
    def build(api, rng):
        args = dict(name="S", mujoco_objects=[plain("a")], x_range=[-0.1, 0.1],
                    y_range=[-0.1, 0.1], reference_pos=(0, 0, 0.8), rng=rng)
        args.update(kwargs)
        if callable(args["mujoco_objects"]):
            args["mujoco_objects"] = args["mujoco_objects"]()
        return api.UniformRandomSampler(**args)
    return build


def hidden(api, rng):
    composite = api.SequentialCompositeSampler("C")
    composite.append_sampler(uniform()(api, rng))
    composite.hide(plain("hidden"))
    return composite


ERRORS = [
    ("reversed x range", uniform(x_range=[0.1, -0.1]), {}, ValueError, "high - low < 0", 0),
    ("reversed y range: x drawn first", uniform(y_range=[0.1, -0.1]), {}, ValueError,
     "high - low < 0", 1),
    ("x range without bound", uniform(x_range=[0, np.inf]), {}, OverflowError,
     "high - low range exceeds valid bounds", 0),
    ("shrink reverses the range", uniform(x_range=[-0.01, 0.01]), {}, ValueError,
     "high - low < 0", 0),
    ("rotation axis: raised after the rotation draw", uniform(rotation_axis="w"), {}, ValueError,
     "Invalid rotation axis specified. Must be 'x', 'y', or 'z'. Got: w", 3),
    ("empty rotation range", uniform(rotation=[]), {}, ValueError,
     "max() arg is an empty sequence", 2),
    ("rotation range without bound", uniform(rotation=(0, np.inf)), {}, OverflowError,
     "high - low range exceeds valid bounds", 2),
    ("name of a fixture", uniform(mujoco_objects=lambda: [plain("mug")]),
     {"fixtures": robosuite_setups.FIXTURES}, AssertionError,
     "Object 'mug' has already been sampled!", 0),
    ("two objects of one name", uniform(mujoco_objects=lambda: [plain("a"), plain("a")]), {},
     AssertionError, "Object 'a' has already been sampled!", 3),
    ("unknown reference", uniform(), {"reference": "table"}, AssertionError,
     "Invalid reference received. Current options are: dict_keys([]), requested: table", 0),
    ("reference of two numbers", uniform(), {"reference": (0, 0)}, AssertionError,
     "Invalid reference received. Should be (x,y,z) 3-tuple, but got: [0 0]", 0),
    ("reference of one number", uniform(), {"reference": 5}, IndexError,
     "tuple index out of range", 0),
    ("x range of one number", uniform(x_range=[0.1]), {}, ValueError,
     "not enough values to unpack (expected 2, got 1)", 0),
    ("object without a radius", uniform(mujoco_objects=lambda: [types.SimpleNamespace(
        name="bare", bottom_offset=np.zeros(3), top_offset=np.zeros(3))]), {}, AttributeError,
     "'types.SimpleNamespace' object has no attribute 'horizontal_radius'", 0),
    ("init_quat of three numbers", uniform(mujoco_objects=lambda: [plain("a", init_quat=[0, 0, 1])]),
     {}, ValueError, "not enough values to unpack (expected 4, got 3)", 3),
    ("hidden objects: robosuite's hide sampler reverses its range", hidden, {}, ValueError,
     "high - low < 0", 3),
    ("a reference at integer coordinates, on top", uniform(),
     {"reference": "table", "fixtures": {"table": ((0, 0, 1), None, plain("table"))}},
     casting_error(),
     "Cannot cast ufunc 'add' output from dtype('float64') to dtype('int64') with casting rule "
     "'same_kind'", 0),
]


class Behaviour(unittest.TestCase):
    """robosuite's exceptions at robosuite's point of the draws, its bookkeeping methods and
    quirks; against robosuite's own code too when ROBOSUITE_PLACEMENT_SAMPLERS is set."""

    @classmethod
    def setUpClass(cls):
        cls.robosuite = load_robosuite()

    def test_exceptions_where_robosuite_raises_them(self):
        for label, build, kwargs, error, message, draws in ERRORS:
            with self.subTest(label):
                rng = np.random.default_rng(99)
                result = outcome(build(ours, rng), kwargs)
                self.assertIsNotNone(result[1], label)
                self.assertIs(type(result[1]), error, "%s: %r" % (label, result[1]))
                self.assertEqual(str(result[1]), message)
                self.assertTrue(same_state(rng.bit_generator.state,
                                           after_draws(99, draws).bit_generator.state), label)
                if self.robosuite is not None:
                    other = np.random.default_rng(99)
                    theirs = outcome(build(self.robosuite, other), kwargs)
                    self.assertIsNone(describe_difference(result, theirs), label)
                    self.assertTrue(same_state(other.bit_generator.state,
                                               rng.bit_generator.state), label)

    def test_bookkeeping(self):
        apis = [ours] + ([self.robosuite] if self.robosuite is not None else [])
        for api in apis:
            cube = plain("cube")
            leaf = api.UniformRandomSampler("Leaf", cube)
            self.assertEqual(leaf.mujoco_objects, [cube])
            with self.assertRaises(AssertionError) as raised:
                leaf.add_objects(cube)
            self.assertEqual(str(raised.exception), "Object 'cube' already in sampler!")
            given = [plain("x")]
            other = api.UniformRandomSampler("Other", given)
            self.assertIsNot(other.mujoco_objects, given, "a copy of the list")
            composite = api.SequentialCompositeSampler("C")
            composite.append_sampler(leaf)
            with self.assertRaises(AssertionError) as raised:
                composite.append_sampler(api.UniformRandomSampler("Again", cube))
            self.assertEqual(str(raised.exception),
                             "Object 'cube' already has sampler associated with it!")
            with self.assertRaises(AttributeError) as raised:
                composite.add_objects(plain("y"))
            self.assertEqual(str(raised.exception),
                             "add_objects() should not be called for SequentialCompsiteSamplers!")
            late = plain("late")
            with self.assertRaises(AssertionError) as raised:
                composite.add_objects_to_sampler("Nope", late)
            self.assertEqual(str(raised.exception), "Invalid sub-sampler specified, valid options "
                             "are: odict_keys(['Leaf']), requested: Nope")
            self.assertIn(late, composite.mujoco_objects, "robosuite appends before it checks")
            composite.add_objects_to_sampler("Leaf", plain("more"))
            self.assertEqual([o.name for o in leaf.mujoco_objects], ["cube", "more"])
            composite.reset()
            self.assertEqual((composite.mujoco_objects, leaf.mujoco_objects), ([], []))
            self.assertEqual(list(composite.samplers), ["Leaf"])
            self.assertIsInstance(composite.rng, np.random.Generator)
            self.assertEqual((leaf.x_range, leaf.y_range, leaf.rotation, leaf.rotation_axis,
                              leaf.z_offset), ((0, 0), (0, 0), None, "z", 0.0))

    def test_sample_args_keep_the_first_call_arguments(self):
        # robosuite writes the call's reference and on_top into a stored sample_args dict, so
        # that they stick in later calls.
        for api in [ours] + ([self.robosuite] if self.robosuite is not None else []):
            rng = np.random.default_rng(1)
            composite = api.SequentialCompositeSampler("C")
            args = {}
            composite.append_sampler(uniform()(api, rng), args)
            first = composite.sample(reference=(1.0, 2.0, 3.0), on_top=False)
            self.assertEqual(args, {"reference": (1.0, 2.0, 3.0), "on_top": False})
            second = composite.sample()
            self.assertTrue(0.9 <= first["a"][0][0] <= 1.1 and 0.9 <= second["a"][0][0] <= 1.1)
            self.assertEqual(second["a"][0][2], 3.0, "on_top=False: no bottom offset")

    def test_fixtures_and_other_samplers(self):
        fixtures = collections.OrderedDict(robosuite_setups.FIXTURES)
        rng = np.random.default_rng(2)
        result = uniform()(ours, rng).sample(fixtures=fixtures)
        self.assertIs(type(result), collections.OrderedDict)
        self.assertEqual(list(result), ["mug", "a"])
        self.assertEqual(list(fixtures), ["mug"], "the fixtures are copied")

        class Shifted(ours.UniformRandomSampler):
            """A subclass with its own sample(): called as robosuite calls any sampler."""

            def sample(self, fixtures=None, reference=None, on_top=True):
                placed = super().sample(fixtures, reference, on_top)
                pos, quat, obj = placed["shifted"]
                placed["shifted"] = ((pos[0], pos[1], pos[2] + 1.0), quat, obj)
                return placed

        for theirs in [REFERENCE] + ([self.robosuite] if self.robosuite is not None else []):
            placements = []
            for api, rng in ((ours, np.random.default_rng(4)), (theirs, np.random.default_rng(4))):
                composite = api.SequentialCompositeSampler("C")
                first = Shifted if api is ours else api.UniformRandomSampler
                composite.append_sampler(first("First", plain("shifted", 0.05), [-0.05, 0.05],
                                               [-0.05, 0.05], reference_pos=(0, 0, 0.8), rng=rng))
                composite.append_sampler(api.UniformRandomSampler(
                    "Second", [plain("b%d" % i, 0.03) for i in range(3)], [-0.1, 0.1],
                    [-0.1, 0.1], reference_pos=(0, 0, 0.8), rng=rng))
                placements.append(composite.sample())
            mine, theirs_placed = placements
            self.assertEqual(mine["shifted"][0][2], theirs_placed["shifted"][0][2] + 1.0)
            for name in ("b0", "b1", "b2"):
                self.assertEqual(mine[name][0], tuple(float(v) for v in theirs_placed[name][0]),
                                 "later samplers see the other sampler's placement as it "
                                 "returned it")

    def test_samplers_changed_during_a_call(self):
        # The composite walks its samplers and sample_args as zip() over their values()
        # iterators: what a sampler changes in them during the call shows, or raises, alike.
        def replace(dicts, key, value):
            return lambda c, api, rng, objects: getattr(c, dicts).__setitem__(key, value(
                api, rng, objects))

        def later(api, rng, objects):
            return api.UniformRandomSampler("Later", [objects[2]], [-0.2, 0.2], [-0.2, 0.2],
                                            reference_pos=(0, 0, 0.8), rng=rng)

        actions = {
            "nothing": lambda c, api, rng, objects: None,
            "a sampler moved to the end": lambda c, *_: c.samplers.move_to_end("A"),
            "sample_args moved to the end": lambda c, *_: c.sample_args.move_to_end("A"),
            "a sampler added": replace("samplers", "X", later),
            "a sampler replaced": replace("samplers", "B", later),
            "sample_args replaced": replace("sample_args", "B", lambda *_: {"on_top": False}),
            "a sampler removed": lambda c, *_: c.samplers.pop("B"),
            "sample_args removed": lambda c, *_: c.sample_args.pop("A"),
            "a sampler removed behind the OrderedDict's back":
                lambda c, *_: dict.pop(c.samplers, "B"),
            "cleared and refilled": lambda c, *_: c.sample_args.update(
                (c.sample_args.clear(), dict(A=None, M=None, B=None))[1]),
        }

        class Meddler:
            """A sampler that changes its composite when it samples."""

            def __init__(self, composite, action, api, rng, objects):
                self.name, self.mujoco_objects = "M", []
                self.call = lambda: action(composite, api, rng, objects)

            def sample(self, fixtures=None, reference=None, on_top=True):
                self.call()
                return {}

        def build(api, rng, objects, action, mapping=None):
            composite = api.SequentialCompositeSampler("C")
            composite.append_sampler(api.UniformRandomSampler(
                "A", [objects[0]], [-0.1, 0.1], [-0.1, 0.1], reference_pos=(0, 0, 0.8), rng=rng))
            composite.append_sampler(Meddler(composite, action, api, rng, objects))
            composite.append_sampler(api.UniformRandomSampler(
                "B", [objects[1]], [-0.1, 0.1], [-0.1, 0.1], reference_pos=(0, 0, 0.8), rng=rng))
            if mapping is not None:
                mapping(composite)
            return composite

        def values_of_its_own(composite):
            samplers = list(composite.samplers.values())
            composite.samplers.values = lambda: reversed(samplers)

        cases = [(label, action, None) for label, action in actions.items()]
        cases += [("plain dicts", actions["nothing"], lambda c: (
            setattr(c, "samplers", dict(c.samplers)),
            setattr(c, "sample_args", dict(c.sample_args)))),
                  ("an OrderedDict with values() of its own", actions["nothing"],
                   values_of_its_own)]
        self.assertTrue(ours._ordered_dict_walks())
        for theirs in [REFERENCE] + ([self.robosuite] if self.robosuite is not None else []):
            for label, action, mapping in cases:
                objects = [plain("a"), plain("b"), plain("later")]
                rng, their_rng = np.random.default_rng(6), np.random.default_rng(6)
                mine = outcome(build(ours, rng, objects, action, mapping), {})
                other = outcome(build(theirs, their_rng, objects, action, mapping), {})
                self.assertIsNone(describe_difference(mine, other), label)
                self.assertTrue(same_state(rng.bit_generator.state,
                                           their_rng.bit_generator.state), label)

    def test_randomization_error_is_robosuites_when_robosuite_came_first(self):
        self.assertIs(ours.RandomizationError, RandomizationError)
        code = ("import placement_samplers.robosuite as m; "
                "print(m.RandomizationError.__module__, m.RandomizationError.__name__, "
                "issubclass(m.RandomizationError, Exception))")
        alone = subprocess.run([sys.executable, "-c", code], check=True, stdout=subprocess.PIPE,
                               universal_newlines=True).stdout.split()
        self.assertEqual(alone, ["placement_samplers.robosuite", "RandomizationError", "True"])


SAMPLE_SCENES = None  # the command-line tool (--sample-scenes)


class Batch(unittest.TestCase):
    """sample_scenes(): the arrays of `sample_scenes --output FILE.npz`."""

    CONFIGS = ["config/lift.yaml", "config/pick_place.yaml", "config/default.yaml",
               "test/data/robosuite/crowded.yaml", "config/resting.yaml"]

    def test_same_arrays_as_the_command_line_tool(self):
        if SAMPLE_SCENES is None:
            self.skipTest("no --sample-scenes PROGRAM given")
        for config in self.CONFIGS:
            path = os.path.join(SOURCE, config)
            with tempfile.TemporaryDirectory() as directory:
                out = os.path.join(directory, "scenes.npz")
                subprocess.run([SAMPLE_SCENES, "--config", path, "--seed", "42", "--scenes", "300",
                                "--first-scene", "5000", "--threads", "1", "--output", out],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                expected = dict(np.load(out))
            for threads in (1, 2):
                arrays = ours.sample_scenes(path, 42, 300, first_scene=5000, threads=threads)
                self.assertEqual(list(arrays), list(expected), config)
                for key, value in expected.items():
                    self.assertEqual((arrays[key].dtype, arrays[key].shape),
                                     (value.dtype, value.shape), "%s %s" % (config, key))
                    self.assertEqual(arrays[key].tobytes(), value.tobytes(),
                                     "%s %s" % (config, key))
            if "crowded" in config:
                self.assertFalse(expected["success"].all(), "some crowded scene fails")
            if "resting" in config:
                self.assertGreater(len(set(expected["rest_pose"].ravel())), 2, "poses drawn")

    def test_configuration_as_a_dict(self):
        import yaml
        path = os.path.join(SOURCE, "config/stack.yaml")
        with open(path) as f:
            config = yaml.safe_load(f)
        from_file = ours.sample_scenes(path, 7, 50)
        from_dict = ours.sample_scenes(config, 7, 50)
        for key in from_file:
            self.assertEqual(from_file[key].tobytes(), from_dict[key].tobytes(), key)
        self.assertEqual(list(from_file["names"]), ["cubeA", "cubeB"])
        self.assertEqual(int(from_file["seed"]), 7)
        self.assertEqual(list(from_file["scene"][:3]), [0, 1, 2])
        # Scene i is robosuite's sampler driven by default_rng([seed, i]).
        rng = np.random.default_rng([7, 3])
        placed = robosuite_setups.stack(ours, rng).sample()
        self.assertEqual(tuple(from_file["position"][3, 0]), placed["cubeA"][0])
        self.assertEqual(tuple(from_file["position"][3, 1]), placed["cubeB"][0])

    def test_errors(self):
        bad = {"objects": {"cube": {"shape": "box", "size": [0.04, 0.04, 0.04]}},
               "samplers": [{"name": "S", "objects": ["cube"], "x_range": [0.3, -0.3],
                             "y_range": [-0.1, 0.1]}]}
        with self.assertRaises(ValueError) as raised:
            ours.sample_scenes(bad, 1, 1)
        self.assertIn("<dict>: samplers[0].x_range", str(raised.exception))
        with self.assertRaises(ValueError) as raised:
            ours.sample_scenes({"objects": {"a": {"shape": "box", "size": [1, 1, 1]}},
                                "samplers": [], 3: 4}, 1, 1)
        self.assertIn("expected string keys, got 3", str(raised.exception))
        with self.assertRaises(ValueError) as raised:
            ours.sample_scenes("/nonexistent/file.yaml", 1, 1)
        self.assertIn("/nonexistent/file.yaml", str(raised.exception))
        with self.assertRaises(ValueError) as raised:
            ours.sample_scenes(os.path.join(SOURCE, "config/lift.yaml"), 1, 2, first_scene=2**64 - 1)
        self.assertIn("2^64", str(raised.exception))
        empty = ours.sample_scenes(os.path.join(SOURCE, "config/lift.yaml"), 1, 0)
        self.assertEqual(empty["position"].shape, (0, 1, 3))


if __name__ == "__main__":
    for flag in ("--calls", "--sample-scenes"):
        if flag in sys.argv:
            i = sys.argv.index(flag)
            if flag == "--calls":
                CALLS = int(sys.argv[i + 1])
            else:
                SAMPLE_SCENES = sys.argv[i + 1]
            del sys.argv[i:i + 2]
    unittest.main(verbosity=2)
