#pragma once

// numpy's C side for the Python module: arrays, the float64 cos and sin loops numpy computes
// robosuite's quaternions with, and the state of a PCG64 bit generator. Only
// numpy_support.cpp includes numpy's headers.

#include <Python.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace placement_samplers::python {

/// Imports numpy's C API and checks what the module reads of numpy against numpy itself:
/// the cos and sin loops (numpyCosSin) and the memory layout of PCG64's state
/// (Pcg64StateAccess). Call once, at import, with the GIL.
/// @return false with a Python error set when numpy cannot be imported
bool initNumpy();

/// cos(@p x) and sin(@p x) exactly as numpy's np.cos and np.sin give them for a float64:
/// numpy's own loops (with AVX-512, numpy's are not the C library's), or numpy called from
/// Python when they could not be checked.
/// @p fixed: @p x is a fixed rotation's, asked for again and again (its values are kept).
/// @return false with a Python error set when calling numpy failed
bool numpyCosSin(double x, double& cosine, double& sine, bool fixed = false);

/// True when numpyCosSin() calls numpy's loops directly (checked at import).
bool cosSinLoopsInUse();

/// @p value [@p index] (negative: from the end) for a 1-d float64 numpy array (exactly
/// numpy.ndarray), read in its memory: @return false when @p value is no such array or the
/// index is out of its range (the caller then asks Python).
bool float64ArrayItem(PyObject* value, Py_ssize_t index, double& out);

/// @p value [0] .. [@p count - 1] for a 1-d float64 numpy array (exactly numpy.ndarray) of
/// at least @p count items, read in its memory: @return false when it is no such array.
bool float64ArrayItems(PyObject* value, std::size_t count, double* out);

/// A new 1-d numpy array of float64 / float32 holding @p values (a new reference or nullptr
/// with a Python error).
PyObject* newFloat64Array(const double* values, std::size_t count);
PyObject* newFloat32Array(const float* values, std::size_t count);

/// A new zero-filled C-contiguous numpy array of @p dtype ("float64", "uint32", "uint64",
/// "bool") and @p shape; @p data receives its buffer.
PyObject* newArray(const char* dtype, const std::vector<std::int64_t>& shape, void** data);

/// Finds how numpy lays out a PCG64's state in memory, checked against its state dict
/// (initNumpy() calls it; numpy_pcg64.cpp).
void findPcg64Layout();

/// How the module reads and writes the state of a numpy PCG64: in the bit generator's memory
/// (its layout checked against `bit_generator.state` at import) or through the state dict.
enum class Pcg64StateAccess { Memory, Dict };
Pcg64StateAccess pcg64StateAccess();
/// For tests: use the state dict even where memory would do (@p dict), or memory again when
/// the layout check passed. @return false when memory access is not available
bool setPcg64StateAccess(bool dict);

/// The numpy bit generator behind `bit_generator.capsule` (numpy's bitgen_t), or nullptr
/// with a Python error.
struct BitGen {
  void* state;
  std::uint64_t (*nextUint64)(void*);
  std::uint32_t (*nextUint32)(void*);
  double (*nextDouble)(void*);
  std::uint64_t (*nextRaw)(void*);
};
BitGen* bitGenOf(PyObject* bitGenerator);

/// PCG64's 128-bit state and increment as four 64-bit words {state high, state low, inc high,
/// inc low}, read from / written to @p bitGenerator by the chosen Pcg64StateAccess. numpy's
/// buffered 32-bit output (has_uint32, uinteger) is left as it is: doubles use 64-bit draws.
/// @return false with a Python error set on failure
bool readPcg64State(PyObject* bitGenerator, BitGen* bitgen, std::array<std::uint64_t, 4>& words);
bool writePcg64State(PyObject* bitGenerator, BitGen* bitgen,
                     const std::array<std::uint64_t, 4>& words);

/// numpy.random.Generator, numpy.random.PCG64 (borrowed references, set by initNumpy()).
PyObject* generatorType();
PyObject* pcg64Type();

}  // namespace placement_samplers::python
