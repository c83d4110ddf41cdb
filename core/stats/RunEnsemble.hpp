#pragma once
/// \file RunEnsemble.hpp
/// \brief Seed ensembles: independent runs of the same parameters but the seed, combined (issue #14, item 2).
///
/// `run --seeds 1..8` writes one ordinary run file per seed; `stats` reads several and combines them here:
/// the statistics of the pooled histograms (every run's subsets side by side, so the subset errors come
/// from all of them), and the spread over seeds for D's error (TailAnalysis.hpp).

#include <string>
#include <vector>

#include "core/run/TrappingRun.hpp"
#include "core/stats/TailAnalysis.hpp"

namespace archipelago {

/// The ensemble of `runs` (one run: an ensemble of one).  `names` (same size, or empty) name the runs in
/// messages.  Throws std::invalid_argument with one line when the runs cannot be combined: none; a parameter
/// other than the seed differs (named, with both values); a different orbit range or number of blocks done;
/// the same seed twice (the same orbits would be counted twice).
[[nodiscard]] Ensemble ensembleOf(const std::vector<TrappingState>& runs, const std::vector<std::string>& names = {});

}  // namespace archipelago
