// sample() of the Python samplers: robosuite's walk over the samplers and their sample_args,
// each UniformRandomSampler run by the core library on a context that mirrors the placements
// dict, its draws from the sampler's own rng.

#include <cstring>
#include <string_view>

#include "python/numpy_support.hpp"
#include "python/ordered_values.hpp"
#include "python/py_samplers.hpp"
#include "python/py_values.hpp"
#include "python/sample_call.hpp"

namespace placement_samplers::python {
namespace {

/// robosuite's draws of one UniformRandomSampler run, with the exception it raises part-way
/// (LeafReading::pending) at its point.
class LeafSource : public UniformSource {
 public:
  LeafSource(RngDraws& draws, const PendingError& pending, std::vector<double>& angles)
      : draws_(draws), pending_(pending), angles_(angles) {}

  double uniform(double low, double high, Draw what) override {
    check(what == Draw::X ? Stage::BeforeX
                          : (what == Draw::Y ? Stage::BeforeY : Stage::BeforeRotation));
    const double value = draws_.uniform(low, high);
    if (what == Draw::Y) {
      check(Stage::AfterY);
    }
    return value;
  }

  void rotation(double angle) override {
    angles_.push_back(angle);
    check(Stage::AfterRotation);
    ++object_;
  }

 private:
  void check(Stage stage) const {
    if (pending_.at(object_, stage)) {
      throw *pending_.error;
    }
  }

  RngDraws& draws_;
  const PendingError& pending_;
  std::vector<double>& angles_;
  std::size_t object_ = 0;
};

/// Removes the context's source when the run ends, however it ends.
struct SourceGuard {
  SampleContext& context;
  ~SourceGuard() { context.setUniformSource(nullptr); }
};

std::shared_ptr<UniformRandomSampler> buildCore(const LeafReading& r, std::size_t count) {
  std::vector<ObjectPtr> objects;
  objects.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const ObjectReading& o = r.objects[i];
    auto model = std::make_shared<ObjectModel>();
    model->name = "#" + std::to_string(i);  // names are the dict's keys, kept in Python
    model->horizontalRadius = o.radius;
    model->bottomOffset = Eigen::Vector3d(0.0, 0.0, o.bottom);
    model->topOffset = Eigen::Vector3d(0.0, 0.0, o.top);
    objects.push_back(std::move(model));
  }
  UniformSamplerParams params = r.params;
  params.orientations = false;  // quaternion() computes robosuite's from the angles
  return std::make_shared<UniformRandomSampler>("robosuite", params, objects);
}

/// robosuite's quaternion (w, x, y, z) of an object turned by @p angle: float64, or float32
/// after quat_multiply with its init_quat.
py::object quaternion(const LeafReading& r, const ObjectReading& o, double angle) {
  double q[4] = {0.0, 0.0, 0.0, 0.0};
  if (r.fixedRotationObject) {
    // A rotation numpy turns into numbers itself (a float32, a large integer, ...).
    py::module_ numpy = py::module_::import("numpy");
    PyObject* half = PyNumber_TrueDivide(r.fixedRotationObject.ptr(), py::int_(2).ptr());
    if (half == nullptr) {
      throw py::error_already_set();
    }
    py::object halfObject = py::reinterpret_steal<py::object>(half);
    py::list items;
    items.append(numpy.attr("cos")(halfObject));
    for (int i = 0; i < 3; ++i) {
      items.append(i == r.axis ? numpy.attr("sin")(halfObject) : py::object(py::int_(0)));
    }
    py::object array = numpy.attr("array")(items);
    if (!o.hasInitQuat) {
      return array;
    }
    for (int i = 0; i < 4; ++i) {
      if (!toDouble(py::object(array[py::int_(i)]).ptr(), q[i])) {
        throw py::error_already_set();
      }
    }
  } else {
    if (!numpyCosSin(angle / 2.0, q[0], q[1 + r.axis],
                     r.params.rotation.kind == RotationSpec::Kind::Fixed)) {
      throw py::error_already_set();
    }
    if (!o.hasInitQuat) {
      return py::reinterpret_steal<py::object>(newFloat64Array(q, 4));
    }
  }
  // transform_utils.quat_multiply(quat, init_quat): both read as (x, y, z, w), in float64,
  // the result in float32.
  const double x1 = q[0], y1 = q[1], z1 = q[2], w1 = q[3];
  const double x0 = o.initQuat[0], y0 = o.initQuat[1], z0 = o.initQuat[2], w0 = o.initQuat[3];
  const float product[4] = {
      static_cast<float>(x1 * w0 + y1 * z0 - z1 * y0 + w1 * x0),
      static_cast<float>(-x1 * z0 + y1 * w0 + z1 * x0 + w1 * y0),
      static_cast<float>(x1 * y0 - y1 * x0 + z1 * w0 + w1 * z0),
      static_cast<float>(-x1 * x0 - y1 * y0 - z1 * z0 + w1 * w0),
  };
  return py::reinterpret_steal<py::object>(newFloat32Array(product, 4));
}

/// robosuite's (pos, quat, obj), pos a tuple of three floats.
py::object placement(const Eigen::Vector3d& position, const py::object& quat,
                     const py::object& object) {
  PyObject* pos = PyTuple_New(3);
  py::object posGuard = py::reinterpret_steal<py::object>(pos);
  PyObject* value = pos != nullptr ? PyTuple_New(3) : nullptr;
  py::object valueGuard = py::reinterpret_steal<py::object>(value);
  if (value == nullptr) {
    throw py::error_already_set();
  }
  for (Py_ssize_t i = 0; i < 3; ++i) {
    PyObject* number = PyFloat_FromDouble(position[i]);
    if (number == nullptr) {
      throw py::error_already_set();
    }
    PyTuple_SET_ITEM(pos, i, number);
  }
  PyTuple_SET_ITEM(value, 0, posGuard.release().ptr());
  PyTuple_SET_ITEM(value, 1, quat.inc_ref().ptr());
  PyTuple_SET_ITEM(value, 2, object.inc_ref().ptr());
  return valueGuard;
}

bool truth(py::handle value) {
  const int v = PyObject_IsTrue(value.ptr());
  if (v < 0) {
    throw py::error_already_set();
  }
  return v == 1;
}

void runComposite(PyCompositeSampler& self, SampleCall& call, py::handle reference,
                  py::handle onTop);

/// robosuite's UniformRandomSampler.sample() on the call's placements.
void runUniform(PyUniformSampler& self, SampleCall& call, py::handle reference, bool onTop) {
  LeafReading& r = call.reading();
  readLeaf(self, call.placed(), reference, onTop, r);
  if (r.objects.empty()) {
    return;
  }
  if (r.params.ensureValidPlacement) {
    call.prepareTests(r);  // before the core sampler: it may add an exception to raise
  }
  std::shared_ptr<UniformRandomSampler> core;
  if (r.pending.error) {
    core = buildCore(r, r.pending.object + 1);
  } else {
    std::vector<double>& key = self.core.reading;
    cacheKey(r, key);
    const bool same =
        self.core.sampler && self.core.key.size() == key.size() &&
        std::memcmp(key.data(), self.core.key.data(), key.size() * sizeof(double)) == 0;
    if (!same) {
      self.core.sampler = buildCore(r, r.objects.size());
      self.core.key.swap(key);
    }
    core = self.core.sampler;
  }
  call.keep(core);
  if (!self.rngInfo.is(self.rng)) {
    self.rngInfo = CallerRng(self.rng);
  }
  SampleContext& context = call.context();
  const std::size_t before = context.placements().size();
  call.angles().clear();
  bool placed = false;
  {
    RngDraws draws(self.rngInfo);
    LeafSource source(draws, r.pending, call.angles());
    SourceGuard guard{context};
    context.setUniformSource(&source);
    placed = core->sample(context, Reference::at(r.base), onTop);
    draws.finish();
  }
  if (!placed) {
    PyErr_SetString(randomizationError().ptr(), "Cannot place all objects ):");
    throw py::error_already_set();
  }
  if (r.pending.error) {
    throw *r.pending.error;  // never reached: the run raises it
  }
  call.recordPlacements(r, before);
  PyObject* dict = call.placed().ptr();
  for (std::size_t i = 0; i < r.objects.size(); ++i) {
    const ObjectPlacement& p = context.placements()[before + i];
    const ObjectReading& o = r.objects[i];
    py::object quat = quaternion(r, o, call.angles()[i]);
    py::object value = placement(p.position, quat, o.object);
    // Exactly a dict: an OrderedDict keeps its order only through its own __setitem__.
    const int status = PyDict_CheckExact(dict) ? PyDict_SetItem(dict, o.name.ptr(), value.ptr())
                                               : PyObject_SetItem(dict, o.name.ptr(), value.ptr());
    if (status < 0) {
      throw py::error_already_set();
    }
  }
}

/// True when @p sampler is @p type's (or a subclass that keeps its sample()).
bool nativeOf(py::handle sampler, PyTypeObject* type) {
  if (Py_IS_TYPE(sampler.ptr(), type)) {
    return true;  // the class itself: its sample() is its own
  }
  if (!PyObject_TypeCheck(sampler.ptr(), type)) {
    return false;
  }
  static PyObject* name = PyUnicode_InternFromString("sample");
  return _PyType_Lookup(Py_TYPE(sampler.ptr()), name) == _PyType_Lookup(type, name);
}

/// robosuite's `if arg_name not in s_args: s_args[arg_name] = arg`.
void fillIn(py::handle args, PyObject* key, py::handle value) {
  const bool dict = PyDict_CheckExact(args.ptr());
  const int present =
      dict ? PyDict_Contains(args.ptr(), key) : PySequence_Contains(args.ptr(), key);
  if (present < 0) {
    throw py::error_already_set();
  }
  if (present == 0 && (dict ? PyDict_SetItem(args.ptr(), key, value.ptr())
                            : PyObject_SetItem(args.ptr(), key, value.ptr())) < 0) {
    throw py::error_already_set();
  }
}

void runComposite(PyCompositeSampler& self, SampleCall& call, py::handle reference,
                  py::handle onTop) {
  py::object samplers = self.samplers;  // held: a sampler may replace them
  py::object sampleArgs = self.sampleArgs;
  OrderedValues samplerValues(samplers);
  OrderedValues argValues(sampleArgs);
  for (;;) {
    py::object sampler = samplerValues.next();
    py::object given = sampler ? argValues.next() : py::object();
    if (!given) {
      break;  // zip() stops at the shorter
    }
    // robosuite fills in the call's reference and on_top where the stored args have none,
    // in the stored dict itself.
    static PyObject* referenceKey = PyUnicode_InternFromString("reference");
    static PyObject* onTopKey = PyUnicode_InternFromString("on_top");
    // None: a fresh dict of the call's two, which nothing else sees; no need to make it.
    py::object a = given.is_none() ? py::object() : given;
    if (a) {
      fillIn(a, referenceKey, reference);
      fillIn(a, onTopKey, onTop);
    }
    const bool plain = !a || (PyDict_Check(a.ptr()) && PyDict_GET_SIZE(a.ptr()) == 2);
    py::handle childReference = a ? PyDict_GetItem(a.ptr(), referenceKey) : reference.ptr();
    py::handle childOnTop = a ? PyDict_GetItem(a.ptr(), onTopKey) : onTop.ptr();
    if (plain && nativeOf(sampler, uniformType())) {
      runUniform(native<PyUniformSampler>(sampler), call, childReference, truth(childOnTop));
    } else if (plain && nativeOf(sampler, compositeType())) {
      runComposite(native<PyCompositeSampler>(sampler), call, childReference, childOnTop);
    } else {
      if (!a) {
        a = py::dict();
        fillIn(a, referenceKey, reference);
        fillIn(a, onTopKey, onTop);
      }
      // Any other sampler, called as robosuite calls it.
      py::dict kwargs;
      kwargs["fixtures"] = call.placed();
      for (auto item : py::reinterpret_borrow<py::dict>(py::dict(a))) {
        if (py::str(item.first).equal(py::str("fixtures"))) {
          PyErr_SetString(PyExc_TypeError,
                          "sample() got multiple values for keyword argument 'fixtures'");
          throw py::error_already_set();
        }
        kwargs[item.first] = item.second;
      }
      py::object added = sampler.attr("sample")(**kwargs);
      call.placed().attr("update")(added);
      call.resync();
    }
  }
}

/// The sampler's call buffers, or new ones when they are in use (a nested call).
class CallLease {
 public:
  explicit CallLease(CallSlot& slot) : slot_(slot) {
    if (slot_.busy) {
      own_ = std::make_unique<SampleCall>();
      call_ = own_.get();
    } else {
      slot_.busy = true;
      call_ = slot_.call.get();
    }
  }
  ~CallLease() {
    call_->end();
    if (!own_) {
      slot_.busy = false;
    }
  }
  SampleCall& call() { return *call_; }

 private:
  CallSlot& slot_;
  std::unique_ptr<SampleCall> own_;
  SampleCall* call_ = nullptr;
};

}  // namespace

py::object sampleUniform(PyUniformSampler& self, py::handle fixtures, py::handle reference,
                         py::handle onTop) {
  CallLease lease(self.slot);
  SampleCall& call = lease.call();
  call.start(fixtures);
  runUniform(self, call, reference, truth(onTop));
  return call.placed();
}

py::object sampleComposite(PyCompositeSampler& self, py::handle fixtures, py::handle reference,
                           py::handle onTop) {
  CallLease lease(self.slot);
  SampleCall& call = lease.call();
  call.start(fixtures);
  runComposite(self, call, reference, onTop);
  return call.placed();
}

}  // namespace placement_samplers::python
