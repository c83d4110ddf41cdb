// The Markov model of appendix C (core/markov/MarkovModel.hpp): C(tau), its island term and D for a model of N points
// with trapped segments of given lengths.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/markov/MarkovModel.hpp"
#include "python/Conversions.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

py::dict markovModel(std::vector<std::int64_t> lengths, std::int64_t points, std::int64_t tauMax, double h0) {
  markov::MarkovModel model{std::move(lengths), points};
  markov::validate(model);
  if (auto e = markov::seriesError(model, tauMax, h0)) throw std::invalid_argument(*e);  // core's rule, the CLI's words
  const markov::LumpedObservable h = markov::paperObservable(model, h0);
  markov::checkSeriesMemory(tauMax);  // the three series at once, before the first (issue #23)
  std::vector<double> C, Cis, eps;
  double D = 0, Dmark = 0, Dis = 0;
  {
    py::gil_scoped_release release;
    C = markov::correlation(model, h, tauMax);
    Cis = markov::islandCorrelation(model, tauMax, h0);
    eps = markov::correlationDeviation(model, h, tauMax, h0);
    D = markov::diffusionCoefficient(model, h);
    Dmark = markov::diffusionCoefficientDmark(model, h);
    Dis = markov::islandDiffusionCoefficient(model, h0);
  }
  py::dict d;
  d["C"] = toArray(C);
  d["C_is"] = toArray(Cis);
  d["epsilon"] = toArray(eps);
  d["D"] = D;
  d["D_dmark"] = Dmark;
  d["D_is"] = Dis;
  return d;
}

}  // namespace

void bindMarkov(py::module_& m) {
  m.def("markov", &markovModel, py::arg("segment_lengths"), py::arg("points"), py::kw_only(), py::arg("tau_max") = 100,
        py::arg("h0") = 1.0,
        "The Markov model of appendix C: N points, trapped segments of lengths m_k, the paper's observable (h0 on the\n"
        "trapped points): C(tau) for tau = 0..tau_max (eq. cmark), the island term C_is, epsilon = (C - C_is)/C_is(0),\n"
        "and D by the lumped solve, by eq. (dmark), and D_is.");
}
