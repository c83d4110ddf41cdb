#pragma once
/// \file MarkovTreeExport.hpp
/// \brief The Markov tree's whole computation from a request (what `archipelago-cli markov-tree` and Python's
/// markov_tree() run) and its outputs: JSON (the tree with every rate's source, the lumped chains, the survival on
/// its grid, each level's share, γ(t)) and CSV, both with their provenance.  docs/markov-tree.md.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/atlas/Atlas.hpp"
#include "core/markovtree/MarkovTree.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/stats/TrappingStatistics.hpp"
#include "core/tail/TailSampler.hpp"

namespace archipelago {

/// What to compute besides the tree.  Plain values; validationError() checks them.
struct MarkovTreeRequest {
  double tMax = 1e9;                 ///< the grid's last point (steps), 1 … 1e18; γ's windows end there
  int perDecade = 30;                ///< grid points per decade, 1 … 1000
  std::vector<std::uint64_t> at;     ///< more t (steps, each ≤ 2⁶²): e.g. the tail sampler's levels
  double alpha = 0;                  ///< the run's mean segment length α (steps); 0 with b2 = 0: no P_t, only S(t)
  double b2 = 0;                     ///< the stochastic area b₂ of the run's box
  bool needsP = false;               ///< P_t is what is asked for (the GUI's Model P_t): α and b₂ must be given
  double exponentFrom = 10;          ///< the running exponent's windows start at or above this (steps), ≥ 1
  std::string atlasSource;           ///< where the atlas came from (a file name), recorded in the outputs
  std::string tailSource;            ///< where the tail compared with came from (computeMarkovTree's `tail`), if any
  MarkovTreeOptions barriers;        ///< which barriers the tree takes (all by default; issue 50's ablation)
};

/// The entry numbers docs/markov-tree.md uses at K = 0.1 (the default box): α, the mean segment length of the q = 16
/// `k0.1-minute` run the tail sampler samples (`archipelago-cli stats`), and b₂, `stochastic_area` on a 4096² grid.
/// A front end with no run (no α of its own) offers them, saying where they come from; they hold for K = 0.1 only.
inline constexpr double kMarkovTreeDocsAlpha = 18.9043;
inline constexpr double kMarkovTreeDocsB2 = 1.362484;

/// The entry numbers a front end offers (prefills) for the Markov tree of an atlas of `atlasMap`, each with where it
/// comes from, or 0 with why there is none — never a number of another map (a K = 0.1 α or b₂ offered for an atlas
/// at K = 0.15 would give a model of the wrong size without a word):
///  - α: the shown run's mean segment length (`runAlpha` > 0) when the run's map (K and box) is the atlas's; else
///    kMarkovTreeDocsAlpha when the atlas's map is the docs' (K = 0.1 in the default box); else none;
///  - b₂: kMarkovTreeDocsB2 when the atlas's map is the docs'; else none (measure it: `archipelago-cli stochastic-area`).
struct MarkovTreeEntryOffer {
  double alpha = 0, b2 = 0;  ///< 0: nothing to offer
  std::string alphaSource, b2Source;
};
[[nodiscard]] MarkovTreeEntryOffer markovTreeEntryOffer(const MapParameters& atlasMap,
                                                        const std::optional<MapParameters>& runMap, double runAlpha);

/// The first violated rule, naming the field, or nothing.  α and b₂ go together; when given (or needsP) they follow
/// markovTreeEntryError's rules that need no atlas; computeMarkovTree checks the rest (b₂ ≤ the box's area,
/// w S(1) ≤ 1) once the atlas's tree is built, before its survival.
[[nodiscard]] std::optional<std::string> validationError(const MarkovTreeRequest& r);

struct MarkovTreeResult {
  MarkovTreeRequest request;
  MapParameters map;                         ///< the atlas's
  int atlasDepth = 0;
  std::size_t atlasIslands = 0;
  MarkovTree tree;
  MarkovTreeSurvival survival;               ///< on the grid, with request.at merged in (ascending, distinct)
  std::optional<long double> weight;         ///< w = α Φ_centre / b₂ when α and b₂ are given: P_t = w S(t)
  std::vector<MarkovTreeExponent> exponents;
  std::optional<MarkovTreeComparison> comparison;  ///< against the tail sampler's levels, when a tail was given
  std::vector<MarkovTreeAblationRow> ablation;     ///< with a tail: markovTreeAblation (each variant's reach)
};

/// The tree of `atlas` and its survival, and with `tail` (a tail sampler's state: its reliable levels) the comparison
/// compareMarkovTreeWithTail from kMarkovTreeCompareFrom.  Throws std::invalid_argument for an invalid request, an
/// atlas that cannot make a tree (markovTreeFromAtlas's message), a tail of another map (K and box) than the atlas's,
/// or a tail without α and b₂ (no P_t to compare), an entry that breaks markovTreeEntryError's rules, or a survival
/// whose cost is past the limits (markovTreeCostError: refused before the survival starts); OperationStopped when
/// `stop` is requested (markovTreeSurvival: within milliseconds).
[[nodiscard]] MarkovTreeResult computeMarkovTree(const Atlas& atlas, const MarkovTreeRequest& request,
                                                 const TailState* tail = nullptr, std::stop_token stop = {});

/// The model's P_t = w S(t) on the survival's grid as a Series (x: t in steps, value: P as a double, no error):
/// t = 0 and the points where P is 0 or below the smallest normal double (the exponential tail) are left out, as the
/// JSON leaves them null.  Empty without w (no α and b₂ in the request).
[[nodiscard]] Series markovTreeCurve(const MarkovTreeResult& r);

/// Each atlas level's share of the survivors at t (its part of S(t) / S(t)), level 0 first, or nothing when t is
/// not on the survival's grid or S(t) is 0.
[[nodiscard]] std::optional<std::vector<double>> markovTreeLevelShares(const MarkovTreeSurvival& s, std::uint64_t t);

/// Where a tree came from (its JSON's "provenance", its CSV's header, the report's figure's PNG): the program, the
/// atlas's map, the model, the atlas and its depth, t max, the grid, α, b₂ and w when given, the tail compared with.
[[nodiscard]] Provenance markovTreeProvenance(const MarkovTreeResult& r);

/// The file format's version: 2 is signed (issue 54); files without a version (before) are read unsigned.
inline constexpr int kMarkovTreeFormatVersion = 2;

/// {"format": "archipelago markov tree", "format_version": 2, "program", "provenance", "map", "request", "atlas",
///  "entry", "entry_flux", "residence", "mean_visit", "states", "rates", "lumped", "survival": {"t", "S", "P", "levels", "states"}, "exponents"} and,
///  with a tail, "comparison": {"tail", "factor", "reach", "levels": [{"t", "measured", "measured_error", "model",
///  "log10_model", "ratio", "log10_ratio", "holding_level", "holding_share"}]} (model and ratio null below the
///  smallest double, their log10 always finite), and last "checksum": "sha256:…" (io::jsonChecksum's, as run, tail
///  and atlas files have: any edit is refused on load).
[[nodiscard]] std::string markovTreeJson(const MarkovTreeResult& r);

/// Reads back what markovTreeJson wrote (a signed file, or an unsigned one from before the version): the request,
/// the map, the atlas's depth and islands, w, the tree's states (with the entry flux and the residence) and rates,
/// the survival (t, S, each level's and state's part, the mean visit) and the exponents; the comparison's tail is
/// kept as its source only.  Every invariant of a computed tree is checked: the checksum, the request's rules
/// (validationError), every number finite, each state's container a state before it, its flux, layer and area > 0
/// with area ≤ layer, the rates between a state and its container with per-step probabilities in (0, 1], t
/// increasing, S(t), P(t) and every part of S in [0, 1], S non-increasing, w = α Φ_centre / b₂.  Throws io::BadFile
/// naming the field and its value.
[[nodiscard]] MarkovTreeResult markovTreeFromJson(const std::string& text);
/// "# key: value" provenance lines, then t,S,P,level_0,…,state_<path>,… one row per t.
[[nodiscard]] std::string markovTreeCsv(const MarkovTreeResult& r);

}  // namespace archipelago
