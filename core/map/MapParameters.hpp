#pragma once
/// \file MapParameters.hpp
/// \brief The physical parameters (K, xmin, xmax) of the periodic quadratic map Q*.
///
/// Karney (1983), §2: Q is  y' = y + 2(x² − K),  x' = x + y'  (eq. qu); Q* replaces g(x) = 2(x² − K) by its
/// periodic continuation with period L = xmax − xmin in x (eq. gstar), and the phase space becomes the torus
/// [xmin, xmax) × [−L/2, L/2).  Appendix B requires xmin < −√K, so that the elliptic fixed point (−√K, 0)
/// lies inside the box and the coefficients a, b, c of G(X) are non-negative.

#include <optional>
#include <string>
#include <vector>

namespace archipelago {

/// Parameters of Q*.  Plain values; check them with validate() before building a map.
struct MapParameters {
  double K = 0.1;      ///< the map parameter (dimensionless); any finite value
  double xmin = -0.8;  ///< left edge of the box in x; must be < −√K (K ≥ 0) or < 0 (K < 0)
  double xmax = 0.5;   ///< right edge of the box in x; must exceed xmin

  /// L = xmax − xmin, the period of the torus in both x and y.
  [[nodiscard]] double width() const noexcept { return xmax - xmin; }

  friend bool operator==(const MapParameters&, const MapParameters&) = default;
};

/// The shortest decimal text that reads back as exactly `v` ("0.1", "-0.8", "1e+30", "inf", "nan"): how core's
/// messages print a number, so that −0.8 never shows as "-0.80000000000000004" (std::to_chars, no locale).
[[nodiscard]] std::string shortestDecimal(double v);

/// One violated rule: the parameters it is about (the first is the one to mark) and a one-line message that
/// names them and states the rule in the paper's notation (Unicode: −, √, ≤), numbers printed by
/// shortestDecimal().
struct ParameterError {
  std::vector<std::string> fields;
  std::string message;
  friend bool operator==(const ParameterError&, const ParameterError&) = default;
};

/// Every violated rule of appendix B, in a fixed order (K, xmin, xmax finite; xmin < −√K for K ≥ 0 or
/// xmin < 0 for K < 0; xmax > xmin; L finite), so that a form can mark every wrong field at once.
[[nodiscard]] std::vector<ParameterError> validationErrors(const MapParameters& p);

/// The first of validationErrors(p) (e.g. "xmin = -0.2 must be < −√K = -0.31622776601683794 …"), or nothing
/// when the parameters are valid.
[[nodiscard]] std::optional<std::string> validationError(const MapParameters& p);

/// Throws std::invalid_argument with validationError(p) when p is invalid.
void validate(const MapParameters& p);

}  // namespace archipelago
