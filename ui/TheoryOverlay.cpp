#include "TheoryOverlay.hpp"

namespace archipelago::ui {

std::vector<TheoryCurve> theoryCurves(const TrappingParameters& /*params*/, const TrappingStatistics& /*statistics*/) {
  return {};  // wired to core/theory when that module lands
}

}  // namespace archipelago::ui
