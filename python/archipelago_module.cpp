// The Python module `archipelago` (issue 18): core's public API as NumPy arrays, for notebooks and scripts.
// No maths here: every number comes from core (Karney 1983, Physica D 8; see the C++ headers cited in each
// docstring).  Errors: std::invalid_argument -> ValueError (core's messages, the CLI's), file errors -> OSError,
// a wrong type -> TypeError, too little memory -> MemoryError, no answer for the input (NotFound: no orbit near the
// guess, a lobe not resolved) -> archipelago.NotFoundError, a ValueError.  Long calls release the GIL and stop on Ctrl-C
// (python/Interruption.hpp); arguments and results are converted by python/Conversions.hpp.
//
// One file per topic, as core's modules: each bind_<topic>.cpp defines bind<Topic>(m).

#include <pybind11/pybind11.h>

#include <exception>

#include "core/io/Memory.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"  // NotFound

namespace py = pybind11;
using namespace archipelago;

void bindMap(py::module_& m);        // bind_map.cpp: the exact map N, its coefficients, orbits, J; kernels
void bindRun(py::module_& m);        // bind_run.cpp: archipelago.Run, start, load, merge, presets
void bindPortrait(py::module_& m);   // bind_portrait.cpp: portraits, b2 and the box-invariant values
void bindScan(py::module_& m);       // bind_scan.cpp: the K scan's box, K list and summary of a run
void bindMarkov(py::module_& m);     // bind_markov.cpp: the Markov model of appendix C
void bindTheory(py::module_& m);     // bind_theory.cpp: the small-K theory's shapes
void bindPeriodic(py::module_& m);   // bind_periodic.cpp: periodic orbits and island chains
void bindManifolds(py::module_& m);  // bind_manifolds.cpp: stable and unstable manifolds, the turnstile flux
void bindMeasures(py::module_& m);   // bind_measures.cpp: rotation numbers, island chains, indicator maps
void bindTail(py::module_& m);       // bind_tail.cpp: the tail of P_t beyond brute force
void bindTailScan(py::module_& m);   // bind_tail_scan.cpp: the tail sampler over K, its summary
void bindAtlas(py::module_& m);      // bind_atlas.cpp: the atlas of the islands around islands
void bindMarkovTree(py::module_& m);  // bind_markov_tree.cpp: the Markov tree of an atlas

PYBIND11_MODULE(_archipelago, m) {
  m.doc() = "Archipelago: stickiness of islands around islands in area-preserving maps "
            "(C. F. F. Karney, Long-time correlations in the stochastic regime, Physica D 8, 1983).";
  m.attr("__version__") = ARCHIPELAGO_VERSION;
  // A value of the wrong type met by an explicit cast is a TypeError, not pybind11's RuntimeError ("Unable to
  // cast Python instance…", issue #23).
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::cast_error& e) {
      PyErr_SetString(PyExc_TypeError, e.what());
    } catch (const io::NotEnoughMemory& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    }
  });
  // A computation with no answer for an input in range (no orbit near the guess, a lobe not resolved): its own
  // class, a ValueError, so that a script can tell it from a crash of the program (issue 36).  Registered after the
  // translator above, so tried before it.
  py::register_exception<NotFound>(m, "NotFoundError", PyExc_ValueError);
  bindMap(m);
  bindRun(m);  // before every binding that takes a Run (scan_point), so that their signatures name it
  bindPortrait(m);
  bindScan(m);
  bindMarkov(m);
  bindTheory(m);
  bindPeriodic(m);
  bindManifolds(m);
  bindMeasures(m);
  bindTail(m);
  bindTailScan(m);
  bindAtlas(m);
  bindMarkovTree(m);
}
