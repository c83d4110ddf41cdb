#pragma once
/// \file QuadText.hpp
/// \brief __float128 numbers (the actions, areas and points of the manifolds' computations) as decimal text: the
/// files (ManifoldExport.hpp), the messages (TurnstileFlux.hpp) and the front ends write them this one way.

#include <string>

#include "core/periodic/SmoothQuadraticMap.hpp"  // quad

namespace archipelago {

/// __float128 as text with `digits` significant digits (e.g. "0.003843389302547659406819825701782").
[[nodiscard]] std::string quadText(quad v, int digits = 34);
/// The coordinate `v` of a point whose other coordinate is `other`, to `digits` significant digits of the point:
/// "0" when |v| is below max(|v|, |other|)·10⁻ᵈⁱᵍⁱᵗˢ (round-off of a zero, e.g. y = 7.2e-35 on the symmetry line
/// y = 0: issue 37, finding 14), else quadText(v, digits).
[[nodiscard]] std::string quadCoordinateText(quad v, quad other, int digits);

}  // namespace archipelago
