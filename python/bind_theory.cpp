// The small-K theory of section 4 (core/theory/SmallKTheory.hpp): the shapes of f_t and C_tau, vectorized over
// NumPy arrays.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <stdexcept>

#include "core/map/MapParameters.hpp"
#include "core/theory/SmallKTheory.hpp"

namespace py = pybind11;
using namespace archipelago;

namespace {

// The theory curves' arguments: core's rule (a time t >= 0 and a finite K; anything else is an error, not NaN).
void checkShapeArguments(double t, double K) {
  if (auto e = smallk::shapeArgumentError(t, K)) throw std::invalid_argument(*e);
}

}  // namespace

void bindTheory(py::module_& m) {
  m.def("segment_shape", py::vectorize([](double t, double K) { checkShapeArguments(t, K); return smallk::segmentShape(t, K); }),
        py::arg("t"), py::arg("K"), "The small-K theory's shape of f_t (section 4; t in steps), up to its amplitude.");
  m.def("correlation_shape", py::vectorize([](double tau, double K) { checkShapeArguments(tau, K); return smallk::correlationShape(tau, K); }),
        py::arg("tau"), py::arg("K"), "The small-K theory's shape of C_tau (section 4; tau in steps), up to its amplitude.");
}
