#pragma once
/// \file IndicatorKind.hpp
/// \brief The kinds of orbit measures (OrbitMeasures.hpp's file comment defines each), their names, and which are
/// weighted Birkhoff averages: what the measures and their kernels (MeasureKernels.hpp) both name.

#include <optional>
#include <string>
#include <string_view>

namespace archipelago {

/// What an indicator measures (OrbitMeasures.hpp's file comment defines each).
enum class IndicatorKind { Dig, Rotation, Fli, Megno, Lyapunov };

/// "dig", "rotation", "fli", "megno", "lyapunov".
[[nodiscard]] std::string_view toString(IndicatorKind kind) noexcept;
[[nodiscard]] std::optional<IndicatorKind> parseIndicatorKind(std::string_view name) noexcept;
/// "dig, rotation, fli, megno, lyapunov" (help texts, error messages).
[[nodiscard]] std::string indicatorKindNames();
/// Dig and Rotation: weighted Birkhoff averages over two blocks, with digits and a regular/chaotic verdict.
[[nodiscard]] bool isBirkhoffKind(IndicatorKind kind) noexcept;

}  // namespace archipelago
