#pragma once
/// \file ReportPlan.hpp
/// \brief What each statement of the paper's table needs computed, so that `archipelago-reproduce --only ID` runs
/// only that (and an unknown ID is refused before any work).

#include <set>
#include <string_view>

namespace archipelago::report {

/// The parts of a report.
enum class Need {
  theory,  ///< closed forms and computations (TheoryStatements.hpp): seconds
  smallK,  ///< fig. 3's runs and the decay runs
  k01,     ///< the K = 0.1 run and its q = 1 companion (figs. 6–8)
  b2,      ///< b₂ of the paper-sized box and of the run's box (with the K = 0.1 run for b₂·D)
  atlas,   ///< the atlas of the K = 0.1 run's map and its Markov tree, against the tail sampler (with k01 and b2)
  scan,    ///< §5's K scan
  tailScan,  ///< the tail sampler over K (tail-gamma-K)
  timing,  ///< appendix B's timing
};

/// The part statement `id` needs.  Throws std::out_of_range for an id the paper's table does not have.
[[nodiscard]] Need needOf(std::string_view id);

/// Every part (a whole report).
[[nodiscard]] std::set<Need> allNeeds();

}  // namespace archipelago::report
