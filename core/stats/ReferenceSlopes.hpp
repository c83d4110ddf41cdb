#pragma once
/// \file ReferenceSlopes.hpp
/// \brief The later literature's exponents of the tail of P_t, drawn as reference lines on P_t's plot and set
/// against our running exponent.  They are asymptotic values (t → ∞): labelled so, never called "consistent"
/// with one window of finite t (issue #26): t^−1.57 (Cristadoro & Ketzmerick, PRL 100, 184101, 2008), t^−3/2
/// (Venegeroles, PRL 102, 064101, 2009), t^−1.3 (Shepelyansky 2010, few degrees of freedom) and t^−3 (Chirikov &
/// Shepelyansky, PRL 82, 528, 1999).

#include <string>
#include <vector>

#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {

/// A reference slope t^−γ for the P_t plot.
struct ReferenceSlope {
  double gamma = 0;
  std::string label;      ///< plain: "t^-1.57 (Cristadoro & Ketzmerick 2008)"
  std::string labelRich;  ///< rich text: "t<sup>−1.57</sup> (Cristadoro &amp; Ketzmerick 2008)"
  Series line;            ///< P(t_a)(t/t_a)^−γ sampled on a logarithmic grid (error 0)
};

/// The reference exponents, once: 1.57, 1.5, 1.3, 3 with their sources.
struct ReferenceExponent {
  double gamma;
  const char* source;
};
[[nodiscard]] const std::vector<ReferenceExponent>& referenceExponents();

/// Reference slopes anchored at the data: at t_a, the largest t of `P` where P_t ≥ 100 P_min, P_min being P's
/// smallest positive value (about one segment's share, so some 100 segments lie beyond t_a; the series alone
/// decides it, so the GUI and the CLI agree), each line drawn from t_a/10 to P's largest abscissa.  Empty when
/// P has no such point.
[[nodiscard]] std::vector<ReferenceSlope> referenceSlopes(const Series& P);

}  // namespace archipelago
