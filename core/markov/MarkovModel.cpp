#include "core/markov/MarkovModel.hpp"

#include "core/io/Memory.hpp"
#include "core/limits/Limits.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

// Glossary (MarkovModel.hpp): N points, m_k segment lengths, m = Σ m_k, M segments, n = N − m sea points
// (S, pre-images q_k included), n′ = N − m − M free sea points (S′); the lumped state is F on T plus the
// common value a on S.

namespace archipelago::markov {

std::int64_t MarkovModel::trappedPoints() const noexcept {
  std::int64_t m = 0;
  for (std::int64_t mk : segmentLengths) m += mk;
  return m;
}

std::int64_t MarkovModel::seaPoints() const noexcept { return points - trappedPoints(); }

std::int64_t MarkovModel::freeSeaPoints() const noexcept {
  return seaPoints() - static_cast<std::int64_t>(segmentLengths.size());
}

void validate(const MarkovModel& model) {
  if (model.segmentLengths.empty()) throw std::invalid_argument("the model needs at least one trapped segment");
  std::int64_t m = 0;
  for (std::size_t k = 0; k < model.segmentLengths.size(); ++k) {
    const std::int64_t mk = model.segmentLengths[k];
    if (auto e = rangeError("segment length m_" + std::to_string(k + 1), mk, 1, MarkovModel::kMaxTrappedPoints))
      throw std::invalid_argument(*e);
    m += mk;
    if (m > MarkovModel::kMaxTrappedPoints)
      throw std::invalid_argument("trapped points m = sum m_k must be <= " +
                                  std::to_string(MarkovModel::kMaxTrappedPoints));
  }
  const auto M = static_cast<std::int64_t>(model.segmentLengths.size());
  if (model.points < m + M + 1 || model.points > MarkovModel::kMaxPoints)
    throw std::invalid_argument("N = " + std::to_string(model.points) + " must be m + M + 1 = " +
                                std::to_string(m + M + 1) + " ... 2^53 (at least one sea point that is not a pre-image)");
}

long double LumpedObservable::trappedSum() const noexcept {
  long double s = 0;
  for (const auto& segment : trapped)
    for (double v : segment) s += v;
  return s;
}

long double LumpedObservable::freeSeaSum() const noexcept {
  long double s = trappedSum();
  for (double v : preImages) s += v;
  return -s;
}

void validate(const MarkovModel& model, const LumpedObservable& h) {
  validate(model);
  const std::size_t M = model.segmentLengths.size();
  if (h.trapped.size() != M || h.preImages.size() != M)
    throw std::invalid_argument("the observable must have one trapped array and one pre-image value per segment");
  for (std::size_t k = 0; k < M; ++k) {
    if (static_cast<std::int64_t>(h.trapped[k].size()) != model.segmentLengths[k])
      throw std::invalid_argument("the observable on segment " + std::to_string(k + 1) + " must have m_k values");
    for (double v : h.trapped[k])
      if (!std::isfinite(v)) throw std::invalid_argument("the observable must be finite");
    if (!std::isfinite(h.preImages[k])) throw std::invalid_argument("the observable must be finite");
  }
  const long double sum = h.freeSeaSum();
  const long double least = sum * sum / static_cast<long double>(model.freeSeaPoints());
  if (!std::isfinite(h.freeSeaSquares) || h.freeSeaSquares < least * (1 - 1e-12L))
    throw std::invalid_argument("the sum of squares of h on S' must be finite and >= (sum over S')^2 / n'");
}

LumpedObservable paperObservable(const MarkovModel& model, double h0) {
  validate(model);
  LumpedObservable h;
  for (std::int64_t mk : model.segmentLengths) h.trapped.emplace_back(static_cast<std::size_t>(mk), h0);
  h.preImages.assign(model.segmentLengths.size(), 0.0);
  const long double total = static_cast<long double>(h0) * model.trappedPoints();
  h.freeSeaSquares = static_cast<double>(total * total / static_cast<long double>(model.freeSeaPoints()));
  return h;
}

// The series of a caller that holds C, C_is and ε at once, each made through a long double copy: at m = 1 the
// work bound allows τmax = 2.5·10⁸, about 14 GB (issue #23), so the memory is checked before the work.
void checkSeriesMemory(std::int64_t tauMax) {
  io::checkMemory(static_cast<std::uintmax_t>(tauMax + 1) * MarkovModel::kBytesPerLag,
                  "the Markov model's series up to tau = " + std::to_string(tauMax));
}

std::int64_t maxTau(const MarkovModel& model) noexcept {
  return MarkovModel::kMaxWork / (model.trappedPoints() + 1) - 1;
}

std::optional<std::string> seriesError(const MarkovModel& model, std::int64_t tauMax, double h0) {
  if (auto e = rangeError("tau_max", tauMax, 0, maxTau(model),
                          "5e8/(m + 1) - 1 for m = " + std::to_string(model.trappedPoints())))
    return e;
  if (!std::isfinite(h0)) return std::string("h0 = ") + (std::isnan(h0) ? "nan" : h0 > 0 ? "inf" : "-inf") +
                                 " must be a finite number";
  return std::nullopt;
}

namespace {

// N·C(τ) (eq. cmark) by the lumped chain, in long double.
std::vector<long double> scaledCorrelation(const MarkovModel& model, const LumpedObservable& h, std::int64_t tauMax) {
  validate(model, h);
  if (auto e = seriesError(model, tauMax)) throw std::invalid_argument(*e);
  checkSeriesMemory(tauMax);
  const long double n = static_cast<long double>(model.seaPoints());
  const long double nFree = static_cast<long double>(model.freeSeaPoints());
  const long double seaSum = -h.trappedSum();  // Σ_S h
  std::vector<long double> C(static_cast<std::size_t>(tauMax) + 1);

  long double hh = h.freeSeaSquares;
  for (const auto& segment : h.trapped)
    for (double v : segment) hh += static_cast<long double>(v) * v;
  for (double v : h.preImages) hh += static_cast<long double>(v) * v;
  C[0] = hh;
  if (tauMax == 0) return C;

  // F(1) = P h, lumped (MarkovModel.hpp).
  std::vector<std::vector<long double>> F(h.trapped.size());
  long double lastSum = 0;  // Σ_k h(p_k^(m_k))
  for (std::size_t k = 0; k < F.size(); ++k) {
    const auto& hk = h.trapped[k];
    F[k].resize(hk.size());
    F[k][0] = h.preImages[k];
    for (std::size_t i = 1; i < hk.size(); ++i) F[k][i] = hk[i - 1];
    lastSum += hk.back();
  }
  long double a = (h.freeSeaSum() + lastSum) / n;
  for (std::int64_t tau = 1;; ++tau) {
    long double dot = a * seaSum;
    for (std::size_t k = 0; k < F.size(); ++k)
      for (std::size_t i = 0; i < F[k].size(); ++i) dot += h.trapped[k][i] * F[k][i];
    C[static_cast<std::size_t>(tau)] = dot;
    if (tau == tauMax) break;
    // One step of R: shift each segment, feed its first point from S, and a′ = (n′a + Σ_k F(p_k^(m_k)))/n.
    long double leaving = 0;
    for (auto& Fk : F) {
      leaving += Fk.back();
      for (std::size_t i = Fk.size() - 1; i > 0; --i) Fk[i] = Fk[i - 1];
      Fk[0] = a;
    }
    a = (nFree * a + leaving) / n;
  }
  return C;
}

// N·C_is(τ) = h₀² Σ_k max(m_k − τ, 0).
std::vector<long double> scaledIslandCorrelation(const MarkovModel& model, std::int64_t tauMax, double h0) {
  validate(model);
  if (auto e = lowerBoundError("tauMax", tauMax, 0)) throw std::invalid_argument(*e);
  checkSeriesMemory(tauMax);
  std::vector<long double> C(static_cast<std::size_t>(tauMax) + 1);
  for (std::int64_t tau = 0; tau <= tauMax; ++tau) {
    std::int64_t overlap = 0;
    for (std::int64_t mk : model.segmentLengths) overlap += mk > tau ? mk - tau : 0;
    C[static_cast<std::size_t>(tau)] = static_cast<long double>(h0) * h0 * static_cast<long double>(overlap);
  }
  return C;
}

std::vector<double> divided(const std::vector<long double>& values, long double divisor) {
  std::vector<double> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) out[i] = static_cast<double>(values[i] / divisor);
  return out;
}

}  // namespace

std::vector<double> correlation(const MarkovModel& model, const LumpedObservable& h, std::int64_t tauMax) {
  return divided(scaledCorrelation(model, h, tauMax), static_cast<long double>(model.points));
}

std::vector<double> islandCorrelation(const MarkovModel& model, std::int64_t tauMax, double h0) {
  return divided(scaledIslandCorrelation(model, tauMax, h0), static_cast<long double>(model.points));
}

std::vector<double> correlationDeviation(const MarkovModel& model, const LumpedObservable& h, std::int64_t tauMax,
                                         double h0) {
  std::vector<long double> C = scaledCorrelation(model, h, tauMax);
  const std::vector<long double> Cis = scaledIslandCorrelation(model, tauMax, h0);
  if (!(Cis[0] > 0)) throw std::invalid_argument("h0 must be nonzero and finite (C_is(0) > 0)");
  for (std::size_t t = 0; t < C.size(); ++t) C[t] -= Cis[t];
  return divided(C, Cis[0]);
}

double diffusionCoefficient(const MarkovModel& model, const LumpedObservable& h) {
  validate(model, h);
  const long double N = static_cast<long double>(model.points);
  // y = Q(I − Q)⁻¹ h: y(p_k^(i)) = a_y + s_k(i − 1), a_y = −Σ_{k,i} s_k(i − 1)/N (MarkovModel.hpp).
  std::vector<std::vector<long double>> offset(h.trapped.size());  // s_k(i − 1)
  long double offsetSum = 0;
  for (std::size_t k = 0; k < offset.size(); ++k) {
    long double s = h.preImages[k];
    for (double v : h.trapped[k]) {
      offset[k].push_back(s);
      offsetSum += s;
      s += v;
    }
  }
  const long double ay = -offsetSum / N;
  long double hh = h.freeSeaSquares, hy = ay * -h.trappedSum();  // a_y Σ_S h
  for (std::size_t k = 0; k < offset.size(); ++k) {
    for (std::size_t i = 0; i < offset[k].size(); ++i) {
      const long double v = h.trapped[k][i];
      hh += v * v;
      hy += v * (ay + offset[k][i]);
    }
    hh += static_cast<long double>(h.preImages[k]) * h.preImages[k];
  }
  return static_cast<double>(hh / (2 * N) + hy / N);
}

double diffusionCoefficientDmark(const MarkovModel& model, const LumpedObservable& h) {
  validate(model, h);
  long double sum = h.freeSeaSquares;
  for (std::size_t k = 0; k < h.trapped.size(); ++k) {
    long double segment = h.preImages[k];  // Σ over T′_k = {q_k} ∪ T_k
    for (double v : h.trapped[k]) segment += v;
    sum += segment * segment;
  }
  return static_cast<double>(sum / (2 * static_cast<long double>(model.points)));
}

double islandDiffusionCoefficient(const MarkovModel& model, double h0) {
  validate(model);
  long double squares = 0;
  for (std::int64_t mk : model.segmentLengths) squares += static_cast<long double>(mk) * mk;
  return static_cast<double>(static_cast<long double>(h0) * h0 * squares / (2 * static_cast<long double>(model.points)));
}

}  // namespace archipelago::markov
