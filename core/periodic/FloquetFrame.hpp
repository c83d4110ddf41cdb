#pragma once
/// \file FloquetFrame.hpp
/// \brief The normal-form (Floquet) coordinates of an elliptic periodic orbit at one of its points: the linear map in
/// which DQⁿ there is a rotation (issue 50: a thin island's rays and angles are taken in them).
///
/// At a point c of an elliptic orbit of period n, M = DQⁿ(c) (det 1, |trace| < 2) is conjugate to the rotation by
/// 2πν, cos 2πν = trace/2: M = cos 2πν·I + sin 2πν·G with G = (M − cos 2πν·I)/sin 2πν, G² = −I.  The quadratic form
/// S = J·G (J = [[0, −1], [1, 0]]), signed to be positive definite, is symmetric with det S = 1 and invariant,
/// MᵀSM = S: its level sets are the linearisation's invariant ellipses (the eigen-ellipses).  Its Cholesky factor B
/// (BᵀB = S, upper triangular, det B = 1: orientation kept) takes an offset v = z − c to normal-form coordinates u = Bv,
/// in which the ellipses are circles and M is B⁻¹·R·B with R a rotation by 2πν.  Near a long, thin island's centre the
/// angle of v about c moves by up to ½ − foldMargin turn per application of Qⁿ (the linear map's largest step, where v
/// crosses the ellipses' short axis), that of u by ν exactly: at K = 0.1 about the member of the 2/13 chain on S₁
/// (axis ratio 54, ν = 0.4025) the largest step of v lies 0.0019 turn below half a turn, and a little way out, where
/// the circles are no longer ellipses, steps of more than half a turn are read backwards (the angle "wraps").

#include <optional>

#include "core/map/FixedPointMap.hpp"  // PhysicalPoint
#include "core/periodic/SmoothQuadraticMap.hpp"

namespace archipelago {

struct FloquetFrame {
  smooth::Matrix2<long double> toNormal;    ///< B: an offset from c to normal-form coordinates
  smooth::Matrix2<long double> fromNormal;  ///< B⁻¹
  long double rotation = 0;                 ///< ν ∈ (0, ½): the linear rotation, in turns per application of Qⁿ
  long double axisRatio = 1;                ///< the eigen-ellipses' long axis over their short one
  long double foldMargin = 0.5L;            ///< ½ turn less the largest step of the angle of z − c under the linear map

  /// The offset z − c in normal-form coordinates, and back.
  [[nodiscard]] PhysicalPoint normal(PhysicalPoint offset) const noexcept;
  [[nodiscard]] PhysicalPoint physical(PhysicalPoint u) const noexcept;
};

/// The frame at c, a point of a periodic orbit of period n of Q at parameter K (DQⁿ(c) in long double); nothing when
/// the orbit is not elliptic there (|trace DQⁿ| ≥ 2, or not finite).
[[nodiscard]] std::optional<FloquetFrame> floquetFrame(long double K, PhysicalPoint c, long n);

}  // namespace archipelago
