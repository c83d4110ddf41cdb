#pragma once
/// \file StochasticAreaExport.hpp
/// \brief The convergence curve of b₂ (StochasticArea.hpp) as JSON: the area and the fraction of the box at each
/// checkpoint (stats/StochasticAreaQuantities.hpp), the request and the final value.

#include <string>

#include "core/stochasticarea/StochasticArea.hpp"

namespace archipelago {

/// The convergence curve of b₂ as JSON text.
[[nodiscard]] std::string stochasticAreaJson(const StochasticAreaRequest& request, const StochasticAreaResult& result);

}  // namespace archipelago
