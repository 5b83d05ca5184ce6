"""The sampler setups of robosuite's manipulation environments, for any implementation of
robosuite's sampler API (placement_samplers.robosuite, robosuite's own placement_samplers.py,
or test/python/robosuite_module_test.py's adapter of test/robosuite_reference.py).

Each setup is built from robosuite's constructor arguments as the environments give them
(robosuite/environments/manipulation/lift.py, stack.py, pick_place.py, nut_assembly.py; the
numbers are those of config/*.yaml, which docs/robosuite_configs.md traces), with objects that
carry robosuite's attributes. `objects` selects how they carry them: as plain attributes, or as
properties computed on every read as robosuite's own classes do (BoxObject from its half sizes,
MujocoXMLObject from the sites of its XML tree).
"""

import xml.etree.ElementTree as ET

import numpy as np


class MujocoObject:
    """Stands for robosuite.models.objects.MujocoObject: what isinstance() tests see."""


class PlainObject(MujocoObject):
    """An object whose robosuite attributes are plain attributes."""

    def __init__(self, name, radius, bottom, top, init_quat=None):
        self.name = name
        self.horizontal_radius = radius
        self.bottom_offset = np.array([0.0, 0.0, bottom])
        self.top_offset = np.array([0.0, 0.0, top])
        if init_quat is not None:
            self.init_quat = init_quat


class BoxLike(MujocoObject):
    """Computes its attributes on every read from its half sizes, as robosuite's BoxObject."""

    def __init__(self, name, half_sizes):
        self.name = name
        self.size = list(half_sizes)

    @property
    def horizontal_radius(self):
        return np.linalg.norm(self.size[0:2], 2)

    @property
    def bottom_offset(self):
        return np.array([0, 0, -1 * self.size[2]])

    @property
    def top_offset(self):
        return np.array([0, 0, self.size[2]])


class XmlLike(MujocoObject):
    """Reads its attributes on every read from the sites of an XML body, as robosuite's
    MujocoXMLObject (milk.xml and the others: bottom_site, top_site, horizontal_radius_site)."""

    def __init__(self, name, radius, bottom, top):
        self.name = name
        self.worldbody = ET.fromstring(
            "<worldbody><body name='object'>"
            "<site name='bottom_site' pos='0 0 %r'/><site name='top_site' pos='0 0 %r'/>"
            "<site name='horizontal_radius_site' pos='%r %r 0'/></body></worldbody>"
            % (bottom, top, radius, radius))

    def _site(self, name):
        site = self.worldbody.find("./body/site[@name='%s']" % name)
        return np.array([float(v) for v in site.get("pos").split(" ")])

    @property
    def horizontal_radius(self):
        return self._site("horizontal_radius_site")[0]

    @property
    def bottom_offset(self):
        return self._site("bottom_site")

    @property
    def top_offset(self):
        return self._site("top_site")


def box(name, half_sizes, objects):
    if objects == "plain":
        return PlainObject(name, np.linalg.norm(half_sizes[0:2], 2), -half_sizes[2],
                           half_sizes[2])
    return BoxLike(name, half_sizes)


def xml(name, radius, bottom, top, objects):
    if objects == "plain":
        return PlainObject(name, radius, bottom, top)
    return XmlLike(name, radius, bottom, top)


def lift(api, rng, objects="plain"):
    """Lift: one cube on the table (lift.py, _load_model)."""
    cube = box("cube", [0.021, 0.021, 0.021], objects)
    return api.UniformRandomSampler(
        name="ObjectSampler", mujoco_objects=cube, x_range=[-0.03, 0.03],
        y_range=[-0.03, 0.03], rotation=None, ensure_object_boundary_in_range=False,
        ensure_valid_placement=True, reference_pos=np.array((0, 0, 0.8)), z_offset=0.01, rng=rng)


def stack(api, rng, objects="plain"):
    """Stack: two cubes side by side (stack.py)."""
    cubes = [box("cubeA", [0.02, 0.02, 0.02], objects), box("cubeB", [0.025, 0.025, 0.025], objects)]
    return api.UniformRandomSampler(
        name="ObjectSampler", mujoco_objects=cubes, x_range=[-0.08, 0.08], y_range=[-0.08, 0.08],
        rotation=None, ensure_object_boundary_in_range=False, ensure_valid_placement=True,
        reference_pos=np.array((0, 0, 0.8)), z_offset=0.01, rng=rng)


PICK_PLACE_OBJECTS = [("Milk", 0.025, -0.085, 0.075), ("Bread", 0.03, -0.045, 0.03),
                      ("Cereal", 0.04, -0.10, 0.03), ("Can", 0.025, -0.06, 0.04)]


def pick_place(api, rng, objects="plain"):
    """PickPlace: four objects in bin 1, one fixed visual copy of each in a quarter of bin 2
    (pick_place.py, _get_placement_initializer)."""
    bin1 = np.array((0.1, -0.25, 0.8))
    bin2 = np.array((0.1, 0.28, 0.8))
    bin_size = (0.39, 0.49, 0.82)
    sampler = api.SequentialCompositeSampler(name="ObjectSampler")
    items = [xml(n, r, b, t, objects) for n, r, b, t in PICK_PLACE_OBJECTS]
    sampler.append_sampler(api.UniformRandomSampler(
        name="CollisionObjectSampler", mujoco_objects=items,
        x_range=[-bin_size[0] / 2 + 0.05, bin_size[0] / 2 - 0.05],
        y_range=[-bin_size[1] / 2 + 0.05, bin_size[1] / 2 - 0.05], rotation=None,
        rotation_axis="z", ensure_object_boundary_in_range=True, ensure_valid_placement=True,
        reference_pos=bin1, z_offset=0.0, rng=rng))
    for i, (n, r, b, t) in enumerate(PICK_PLACE_OBJECTS):
        visual = xml("Visual" + n, r, b, t, objects)
        x_lo = bin2[0] - bin_size[0] / 2 if i in (0, 2) else bin2[0]
        y_lo = bin2[1] - bin_size[1] / 2 if i < 2 else bin2[1]
        centre = np.array((x_lo + bin_size[0] / 4, y_lo + bin_size[1] / 4)) - bin1[:2]
        sampler.append_sampler(api.UniformRandomSampler(
            name=visual.name + "ObjectSampler", mujoco_objects=visual,
            x_range=[centre[0], centre[0]], y_range=[centre[1], centre[1]], rotation=0.0,
            rotation_axis="z", ensure_object_boundary_in_range=False,
            ensure_valid_placement=False, reference_pos=bin1, z_offset=bin2[2] - bin1[2],
            rng=rng))
    return sampler


def nut_assembly(api, rng, objects="plain", shrink=False):
    """NutAssembly: a square and a round nut, each with its own sampler (nut_assembly.py).
    With shrink, ensure_object_boundary_in_range is on: the x range is then reversed for the
    nuts' 0.11 m radius, which numpy's Generator refuses."""
    sampler = api.SequentialCompositeSampler(name="ObjectSampler")
    for name, y_range in zip(("SquareNut", "RoundNut"), ([0.11, 0.225], [-0.225, -0.11])):
        sampler.append_sampler(api.UniformRandomSampler(
            name=name + "Sampler", x_range=[-0.115, -0.11], y_range=y_range, rotation=None,
            rotation_axis="z", ensure_object_boundary_in_range=shrink,
            ensure_valid_placement=True, reference_pos=np.array((0, 0, 0.82)), z_offset=0.02,
            rng=rng))
    sampler.add_objects_to_sampler(sampler_name="SquareNutSampler",
                                   mujoco_objects=xml("SquareNut", 0.11, -0.05, 0.01, objects))
    sampler.add_objects_to_sampler(sampler_name="RoundNutSampler",
                                   mujoco_objects=xml("RoundNut", 0.11, -0.05, 0.025, objects))
    return sampler


def crowded(api, rng, objects="plain"):
    """Six discs in a small square: about one call in a hundred cannot place them all."""
    discs = [PlainObject("disc%d" % i, 0.05, -0.02, 0.02) for i in range(6)]
    return api.UniformRandomSampler(
        name="CrowdedSampler", mujoco_objects=discs, x_range=[-0.13, 0.13],
        y_range=[-0.13, 0.13], rotation=None, ensure_object_boundary_in_range=False,
        ensure_valid_placement=True, reference_pos=(0, 0, 0.8), z_offset=0.0, rng=rng)


FIXTURES = {"mug": ((0.04, 0.03, 0.83), np.array([1.0, 0.0, 0.0, 0.0]),
                    PlainObject("mug", 0.04, -0.03, 0.05))}


def stacked(api, rng, objects="plain"):
    """A base cube, a cube on top of it (a named reference, on_top), a tilted plate with an
    init_quat turned about x by a rotation range, a bowl at a fixed angle about y; all beside
    the fixture FIXTURES["mug"]."""
    sampler = api.SequentialCompositeSampler(name="Stacked")
    sampler.append_sampler(api.UniformRandomSampler(
        name="BaseSampler", mujoco_objects=[box("base", [0.03, 0.03, 0.03], objects)],
        x_range=[-0.1, 0.1], y_range=[-0.1, 0.1], rotation=None,
        ensure_object_boundary_in_range=True, reference_pos=(0, 0, 0.8), z_offset=0.0, rng=rng))
    sampler.append_sampler(api.UniformRandomSampler(
        name="TopSampler", mujoco_objects=box("top", [0.02, 0.02, 0.02], objects),
        x_range=[-0.01, 0.01], y_range=[-0.01, 0.01], rotation=(-0.3, 0.3),
        ensure_object_boundary_in_range=False, z_offset=0.002, rng=rng),
        sample_args={"reference": "base", "on_top": True})
    plate = PlainObject("plate", 0.06, -0.01, 0.01,
                        init_quat=np.array([0.0, 0.0, 0.38268343, 0.9238795], dtype=np.float32))
    sampler.append_sampler(api.UniformRandomSampler(
        name="PlateSampler", mujoco_objects=plate, x_range=[-0.2, 0.2], y_range=[-0.2, 0.2],
        rotation=[0.1, -0.2, 0.4], rotation_axis="x", reference_pos=(0, 0, 0.8), rng=rng))
    bowl = PlainObject("bowl", 0.05, -0.025, 0.025, init_quat=[0.5, 0.5, 0.5, 0.5])
    sampler.append_sampler(api.UniformRandomSampler(
        name="BowlSampler", mujoco_objects=bowl, x_range=[-0.2, 0.2], y_range=[-0.2, 0.2],
        rotation=0.7, rotation_axis="y", reference_pos=np.array((0, 0, 0.8)), rng=rng),
        sample_args={"on_top": False})
    return sampler


SETUPS = {"lift": lift, "stack": stack, "pick_place": pick_place, "nut_assembly": nut_assembly,
          "crowded": crowded, "stacked": stacked}
