#pragma once
// The Markov model of appendix C with plain N × N matrices, for small N: the reference that the lumped
// implementation (core/markov/MarkovModel.hpp) is checked against.  Test-only; O(N²) memory, O(N³) time.
//
// Point order: T_1, …, T_M (each in segment order), then S′, then the pre-images q_1, …, q_M, so that
// N = 7, m = 3 is exactly eq. (pex): points 1–3 trapped, 4–6 free sea, 7 the pre-image.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/markov/MarkovModel.hpp"

namespace archipelago::markov::dense {

using Matrix = std::vector<std::vector<double>>;  // Matrix[j][i]: from point i to point j

struct Layout {
  std::vector<std::vector<std::size_t>> segments;  // indices of p_k^(1..m_k)
  std::vector<std::size_t> freeSea;                // S′
  std::vector<std::size_t> preImages;              // q_k
};

inline Layout layout(const std::vector<std::int64_t>& lengths, std::size_t N) {
  Layout L;
  std::size_t next = 0;
  for (std::int64_t mk : lengths) {
    L.segments.emplace_back();
    for (std::int64_t i = 0; i < mk; ++i) L.segments.back().push_back(next++);
  }
  const std::size_t firstPreImage = N - lengths.size();
  while (next < firstPreImage) L.freeSea.push_back(next++);
  while (next < N) L.preImages.push_back(next++);
  return L;
}

// P of appendix C written out from its rules (not from the lumped chain).
inline Matrix transitionMatrix(const std::vector<std::int64_t>& lengths, std::size_t N) {
  const Layout L = layout(lengths, N);
  Matrix P(N, std::vector<double>(N, 0.0));
  std::vector<std::size_t> sea = L.freeSea;  // S = S′ ∪ {q_k}
  sea.insert(sea.end(), L.preImages.begin(), L.preImages.end());
  const double uniform = 1.0 / static_cast<double>(sea.size());
  auto toSea = [&](std::size_t from) {
    for (std::size_t j : sea) P[j][from] = uniform;
  };
  for (std::size_t k = 0; k < L.segments.size(); ++k) {
    const auto& T = L.segments[k];
    P[T.front()][L.preImages[k]] = 1;                      // q_k → p_k^(1)
    for (std::size_t i = 0; i + 1 < T.size(); ++i) P[T[i + 1]][T[i]] = 1;  // p^(i) → p^(i+1)
    toSea(T.back());                                       // p^(m_k) → uniform on S
  }
  for (std::size_t i : L.freeSea) toSea(i);                // S′ → uniform on S
  return P;
}

inline std::vector<double> multiply(const Matrix& P, const std::vector<double>& F) {
  std::vector<double> out(F.size(), 0.0);
  for (std::size_t j = 0; j < P.size(); ++j)
    for (std::size_t i = 0; i < F.size(); ++i) out[j] += P[j][i] * F[i];
  return out;
}

inline double dot(const std::vector<double>& a, const std::vector<double>& b) {
  long double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += static_cast<long double>(a[i]) * b[i];
  return static_cast<double>(s);
}

// C(τ) = h·Pᵗ·h/N, eq. (cmark), τ = 0 … tauMax.
inline std::vector<double> correlation(const Matrix& P, const std::vector<double>& h, std::size_t tauMax) {
  const double N = static_cast<double>(h.size());
  std::vector<double> C;
  std::vector<double> F = h;
  for (std::size_t tau = 0; tau <= tauMax; ++tau) {
    C.push_back(dot(h, F) / N);
    F = multiply(P, F);
  }
  return C;
}

// x = A⁻¹ b by Gaussian elimination with partial pivoting.
inline std::vector<double> solve(Matrix A, std::vector<double> b) {
  const std::size_t n = b.size();
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::fabs(A[r][c]) > std::fabs(A[pivot][c])) pivot = r;
    if (A[pivot][c] == 0) throw std::runtime_error("singular matrix");
    std::swap(A[c], A[pivot]);
    std::swap(b[c], b[pivot]);
    for (std::size_t r = c + 1; r < n; ++r) {
      const double f = A[r][c] / A[c][c];
      if (f == 0) continue;
      for (std::size_t k = c; k < n; ++k) A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  std::vector<double> x(n);
  for (std::size_t r = n; r-- > 0;) {
    double s = b[r];
    for (std::size_t k = r + 1; k < n; ++k) s -= A[r][k] * x[k];
    x[r] = s / A[r][r];
  }
  return x;
}

// D = h·(½I + Q(I − Q)⁻¹)·h/N with Q = P − C, C = [1/N] (appendix C).
inline double diffusionCoefficient(const Matrix& P, const std::vector<double>& h) {
  const std::size_t n = h.size();
  const double N = static_cast<double>(n);
  Matrix Q = P;
  for (auto& row : Q)
    for (double& v : row) v -= 1 / N;
  Matrix IminusQ = Q;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) IminusQ[j][i] = (i == j ? 1.0 : 0.0) - Q[j][i];
  const std::vector<double> y = solve(IminusQ, h);
  return dot(h, h) / (2 * N) + dot(h, multiply(Q, y)) / N;
}

// The full vector h (in the order of layout()) as the lumped observable of MarkovModel.hpp.
inline LumpedObservable lump(const std::vector<std::int64_t>& lengths, const std::vector<double>& h) {
  const Layout L = layout(lengths, h.size());
  LumpedObservable lumped;
  for (const auto& T : L.segments) {
    lumped.trapped.emplace_back();
    for (std::size_t i : T) lumped.trapped.back().push_back(h[i]);
  }
  for (std::size_t i : L.preImages) lumped.preImages.push_back(h[i]);
  long double squares = 0;
  for (std::size_t i : L.freeSea) squares += static_cast<long double>(h[i]) * h[i];
  lumped.freeSeaSquares = static_cast<double>(squares);
  return lumped;
}

}  // namespace archipelago::markov::dense
