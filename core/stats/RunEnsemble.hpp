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
#include "core/stats/TrappingStatistics.hpp"
#include "core/trapping/TrappingHistogram.hpp"

namespace archipelago {

/// One independent run of an ensemble: its subset histograms, the orbits behind each, and its seed.
struct EnsembleMember {
  std::vector<TrappingHistogram> subsets;
  std::vector<std::uint64_t> orbitsPerSubset;
  std::uint64_t seed = 0;
};

/// Independent runs of the same parameters but the seed (one run: one member), all over `blocks` blocks.
struct Ensemble {
  std::vector<EnsembleMember> members;
  std::uint64_t blocks = 0;  ///< T (blocks done) of every member
  std::uint32_t q = 1;
};

/// The pooled subsets of an ensemble (every member's subsets, in member order) and their orbit counts.
[[nodiscard]] std::vector<TrappingHistogram> pooledSubsets(const Ensemble& e);
[[nodiscard]] std::vector<std::uint64_t> pooledOrbitsPerSubset(const Ensemble& e);
/// The statistics of the pooled histograms, errors from the spread over all subsets of all members.
/// Throws std::invalid_argument as computeStatistics() does, or for an ensemble without members.
[[nodiscard]] TrappingStatistics ensembleStatistics(const Ensemble& e);

/// The ensemble of `runs` (one run: an ensemble of one).  `names` (same size, or empty) name the runs in
/// messages.  Throws std::invalid_argument with one line when the runs cannot be combined: none; a parameter
/// other than the seed differs (named, with both values); a different orbit range or number of blocks done;
/// the same seed twice (the same orbits would be counted twice).
[[nodiscard]] Ensemble ensembleOf(const std::vector<TrappingState>& runs, const std::vector<std::string>& names = {});

}  // namespace archipelago
