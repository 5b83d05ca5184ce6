#include "python/numpy_support.hpp"

// Only numpy_support.cpp imports numpy's array API; this file uses none of it.
#include <cstring>

namespace placement_samplers::python {
namespace {

/// numpy's pcg64_state (numpy/random/src/pcg64/pcg64.h), which the capsule's state points
/// to: the generator's {state, inc} (two 128-bit words), then the 32-bit output buffer.
struct NumpyPcg64State {
  void* pcgState;
  int hasUint32;
  std::uint32_t uinteger;
};

/// Where the 64-bit halves sit in {state, inc}: numpy's native unsigned __int128 (low half
/// first on little-endian machines) or its emulated {high, low} pairs.
enum class Pcg64Layout { Unknown, LowFirst, HighFirst };

Pcg64Layout gLayout = Pcg64Layout::Unknown;
bool gForceDict = false;

bool splitInt(PyObject* value, std::uint64_t& high, std::uint64_t& low) {
  PyObject* shift = PyLong_FromLong(64);
  PyObject* highObject = shift != nullptr ? PyNumber_Rshift(value, shift) : nullptr;
  Py_XDECREF(shift);
  if (highObject == nullptr) {
    return false;
  }
  high = PyLong_AsUnsignedLongLong(highObject);
  Py_DECREF(highObject);
  low = PyLong_AsUnsignedLongLongMask(value);
  return !PyErr_Occurred();
}

PyObject* joinInt(std::uint64_t high, std::uint64_t low) {
  PyObject* h = PyLong_FromUnsignedLongLong(high);
  PyObject* shift = PyLong_FromLong(64);
  PyObject* shifted = h != nullptr && shift != nullptr ? PyNumber_Lshift(h, shift) : nullptr;
  Py_XDECREF(h);
  Py_XDECREF(shift);
  PyObject* l = PyLong_FromUnsignedLongLong(low);
  PyObject* out = shifted != nullptr && l != nullptr ? PyNumber_Or(shifted, l) : nullptr;
  Py_XDECREF(shifted);
  Py_XDECREF(l);
  return out;
}

/// The {'state': S, 'inc': I} of a PCG64's state dict (borrowed from @p dict).
bool dictWords(PyObject* dict, std::array<std::uint64_t, 4>& words) {
  PyObject* inner = PyDict_Check(dict) ? PyDict_GetItemString(dict, "state") : nullptr;
  PyObject* state =
      inner != nullptr && PyDict_Check(inner) ? PyDict_GetItemString(inner, "state") : nullptr;
  PyObject* inc =
      inner != nullptr && PyDict_Check(inner) ? PyDict_GetItemString(inner, "inc") : nullptr;
  if (state == nullptr || inc == nullptr) {
    PyErr_SetString(PyExc_TypeError, "PCG64.state: expected {'state': {'state': ..., 'inc': ...}}");
    return false;
  }
  return splitInt(state, words[0], words[1]) && splitInt(inc, words[2], words[3]);
}

std::uint64_t* memoryWords(BitGen* bitgen) {
  return static_cast<std::uint64_t*>(static_cast<NumpyPcg64State*>(bitgen->state)->pcgState);
}

bool readMemory(BitGen* bitgen, std::array<std::uint64_t, 4>& words) {
  const std::uint64_t* w = memoryWords(bitgen);
  const bool lowFirst = gLayout == Pcg64Layout::LowFirst;
  words = {w[lowFirst ? 1 : 0], w[lowFirst ? 0 : 1], w[lowFirst ? 3 : 2], w[lowFirst ? 2 : 3]};
  return true;
}

void writeMemory(BitGen* bitgen, const std::array<std::uint64_t, 4>& words) {
  std::uint64_t* w = memoryWords(bitgen);
  const bool lowFirst = gLayout == Pcg64Layout::LowFirst;
  w[0] = lowFirst ? words[1] : words[0];
  w[1] = lowFirst ? words[0] : words[1];
  w[2] = lowFirst ? words[3] : words[2];
  w[3] = lowFirst ? words[2] : words[3];
}

bool readDict(PyObject* bitGenerator, std::array<std::uint64_t, 4>& words) {
  PyObject* dict = PyObject_GetAttrString(bitGenerator, "state");
  if (dict == nullptr) {
    return false;
  }
  const bool ok = dictWords(dict, words);
  Py_DECREF(dict);
  return ok;
}

bool writeDict(PyObject* bitGenerator, const std::array<std::uint64_t, 4>& words) {
  // The current dict with the new state and inc: has_uint32 and uinteger stay as they are.
  PyObject* dict = PyObject_GetAttrString(bitGenerator, "state");
  PyObject* inner =
      dict != nullptr && PyDict_Check(dict) ? PyDict_GetItemString(dict, "state") : nullptr;
  PyObject* state = joinInt(words[0], words[1]);
  PyObject* inc = joinInt(words[2], words[3]);
  bool ok = inner != nullptr && PyDict_Check(inner) && state != nullptr && inc != nullptr &&
            PyDict_SetItemString(inner, "state", state) == 0 &&
            PyDict_SetItemString(inner, "inc", inc) == 0 &&
            PyObject_SetAttrString(bitGenerator, "state", dict) == 0;
  if (!ok && !PyErr_Occurred()) {
    PyErr_SetString(PyExc_TypeError, "PCG64.state: unexpected layout");
  }
  Py_XDECREF(state);
  Py_XDECREF(inc);
  Py_XDECREF(dict);
  return ok;
}

/// Finds where numpy keeps the halves: a PCG64 read in memory and through its state dict,
/// written in memory and read back, and its next double against what memory says it is.
Pcg64Layout checkLayout() {
  PyObject* bitGenerator = PyObject_CallFunction(pcg64Type(), "K", 20240605ULL);
  if (bitGenerator == nullptr) {
    PyErr_Clear();
    return Pcg64Layout::Unknown;
  }
  Pcg64Layout found = Pcg64Layout::Unknown;
  BitGen* bitgen = bitGenOf(bitGenerator);
  std::array<std::uint64_t, 4> expected{};
  if (bitgen != nullptr && readDict(bitGenerator, expected)) {
    const std::uint64_t* w = memoryWords(bitgen);
    if (w[0] == expected[1] && w[1] == expected[0] && w[2] == expected[3] && w[3] == expected[2]) {
      found = Pcg64Layout::LowFirst;
    } else if (w[0] == expected[0] && w[1] == expected[1] && w[2] == expected[2] &&
               w[3] == expected[3]) {
      found = Pcg64Layout::HighFirst;
    }
  }
  if (found != Pcg64Layout::Unknown) {
    // Written in memory, read through the dict.
    gLayout = found;
    const std::array<std::uint64_t, 4> chosen = {0x0123456789abcdefULL, 0xfedcba9876543210ULL,
                                                 0x1111111111111111ULL, 0x2222222222222223ULL};
    writeMemory(bitgen, chosen);
    std::array<std::uint64_t, 4> back{};
    if (!readDict(bitGenerator, back) || back != chosen) {
      found = Pcg64Layout::Unknown;
    }
  }
  PyErr_Clear();
  Py_DECREF(bitGenerator);
  gLayout = Pcg64Layout::Unknown;
  return found;
}

}  // namespace

void findPcg64Layout() { gLayout = checkLayout(); }

Pcg64StateAccess pcg64StateAccess() {
  return gLayout != Pcg64Layout::Unknown && !gForceDict ? Pcg64StateAccess::Memory
                                                        : Pcg64StateAccess::Dict;
}

bool setPcg64StateAccess(bool dict) {
  gForceDict = dict;
  return gLayout != Pcg64Layout::Unknown;
}

BitGen* bitGenOf(PyObject* bitGenerator) {
  PyObject* capsule = PyObject_GetAttrString(bitGenerator, "capsule");
  if (capsule == nullptr) {
    return nullptr;
  }
  // The capsule lives as long as the bit generator, which the caller holds.
  auto* bitgen = static_cast<BitGen*>(PyCapsule_GetPointer(capsule, "BitGenerator"));
  Py_DECREF(capsule);
  return bitgen;
}

bool readPcg64State(PyObject* bitGenerator, BitGen* bitgen, std::array<std::uint64_t, 4>& words) {
  if (pcg64StateAccess() == Pcg64StateAccess::Memory) {
    return readMemory(bitgen, words);
  }
  return readDict(bitGenerator, words);
}

bool writePcg64State(PyObject* bitGenerator, BitGen* bitgen,
                     const std::array<std::uint64_t, 4>& words) {
  if (pcg64StateAccess() == Pcg64StateAccess::Memory) {
    writeMemory(bitgen, words);
    return true;
  }
  return writeDict(bitGenerator, words);
}

}  // namespace placement_samplers::python
