#pragma once
/// \file MarkovTree.hpp
/// \brief The Meiss–Ott Markov tree of the island hierarchy, built from the atlas (issue 40): one state per region
/// between successive barriers, transition probabilities per step = flux / area, and the survival P_t of the finite
/// absorbing chain computed exactly (no simulation, no fitted parameter).  docs/markov-tree.md derives it.
///
/// Meiss & Ott, Physica D 20 (1986) 387; MacKay, Meiss & Percival, Physica D 13 (1984) 55; Meiss, RMP 64 (1992) 795.
/// Karney's appendix-C model (core/markov) is another thing: a sea and segments of fixed lengths.
///
/// **The states.**  The barriers about each island, from outside in (issue 50): each chain's outer separatrix (the
/// loop of (√K, 0) at the centre), its inner separatrix (AtlasFlux::inner, when its layer is settled), and between two
/// successive chains about an island the cantorus of the noble rotation between them, and inside the innermost chain
/// about an island its boundary cantorus (Atlas::cantori, when found).
/// Each encloses a zone whose layer ℓ (the zone less the atlas's islands inside it) an orbit that crossed it moves
/// in.  The chains about one island nest, ordered by zone area and checked against the twist (the farther a chain's
/// p/q from the island's boundary rotation, the farther out it lies).  The state of barrier b is its layer less the
/// layers of the barriers just inside it (its children), A_b = ℓ_b − Σ ℓ_children, opening onto the state just outside
/// (its container).  Just inside a chain's outer separatrix lie the next barrier about the same island and the
/// outermost chain about its own islands (which lie between its separatrices): the tree branches there.  Every layer
/// but the centre's is subtracted once, so Σ A = ℓ_centre.  (The literal tree — each island's layer less all its
/// children's — would subtract the nested layers several times: at K = 0.1 the centre's would be negative.)
/// MarkovTreeOptions leaves inner separatrices, cantori or deep levels out (issue 50's ablation).
///
/// **The rates.**  Through barrier c (flux Φ_c, the turnstile lobe of its chain: area crossing per step each way):
/// state c → its container with probability Φ_c / A_c per step, container → c with Φ_c / A_container; the top state
/// → the sea with Φ_centre / A_centre.  Area is preserved, so the chain is reversible with the areas as its
/// measure; the mean time to absorption from the top is ℓ_centre / Φ_centre (Kac), the atlas's residence of the loop.
///
/// **Left out.**  A chain without a flux (refused, period above the flux search's 400, no primary pair, not found)
/// has no barrier: it and its whole subtree are lumped into the state around them (their layers are part of it, their
/// islands were subtracted by the atlas); MarkovTree::lumped lists each with the atlas's reason.
///
/// **P_t.**  A visit to the loop's zone enters the top state (the entry lobe lies outside every inner barrier); its
/// survival is S(t) = e_top · Mᵗ · 1, M the substochastic matrix of the rates.  The run process's segments start in
/// the sea (after a wrap or a randomization, appendix B), enter the loop's zone Φ_centre / b₂ times per step (Kac:
/// the process's invariant measure is uniform on the stochastic area b₂) and end 1/α times per step, so a segment
/// makes w = α Φ_centre / b₂ visits on average, and for t well above the sea's time scale P_t = w · S(t) (docs).
/// Mᵗ from the eigen-decomposition of the symmetric matrix similar to G = I − M (the chain is reversible with the
/// areas as its measure), in long double, at any t: each mode's (1 − μ)ᵗ from μ (no cancellation against 1 for the
/// slow modes, μ ~ 10⁻¹⁰), each μ refined as its eigenvector's Dirichlet form (a sum of positive terms: good to its
/// own rounding, not only to 2⁻⁶³ ‖G‖); up to t = kMarkovTreeDirectSteps by t products with M in quad instead, exact.
/// Cost (markovTreeCost, issue 54): 16 (n² + n m) bytes and about 10 n³ + 2 n² m operations for n states and m times
/// (10 states at K = 0.1 depth 2: a millisecond; 1000: seconds); past core/limits' "markov tree states" or "markov
/// tree survival values" it is refused up front, with its cost.  (The binary powering of M in quad that came before
/// cost n³ log₂ t quad operations and a matrix per power: a legal atlas of 1000 nesting chains ran past 360 s, one of
/// 20,000 asked 6.4 GB per power.)

#include <cstdint>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/atlas/Atlas.hpp"
#include "core/stats/LogFits.hpp"
#include "core/tail/TailResult.hpp"

namespace archipelago {

/// What bounds a state (issue 50): a chain's outer separatrix (the centre's loop for the top state), its inner one,
/// or a cantorus between two chains about the centre.
enum class MarkovTreeBarrier { OuterSeparatrix, InnerSeparatrix, Cantorus };
[[nodiscard]] const char* toString(MarkovTreeBarrier b);

/// A state of the tree: the region inside its barrier less the regions inside the barriers just inside it.
struct MarkovTreeState {
  int node = 0;                 ///< the atlas node whose separatrix bounds it (0: the centre's loop; −1: a cantorus)
  MarkovTreeBarrier barrier = MarkovTreeBarrier::OuterSeparatrix;
  std::string path;             ///< its atlas path ("centre", "6 > 138"); "13 inner", "cantorus 5/31-1/6"
  int level = 0;                ///< that node's level in the atlas
  int container = -1;           ///< the state beyond its barrier (−1: the sea)
  long double flux = 0;         ///< Φ through its barrier: atlas nodes[node].flux.flux
  long double layer = 0;        ///< ℓ: atlas nodes[node].flux.layerArea
  std::vector<int> subtracted;  ///< the states just inside it (its children), whose barriers' layers are subtracted
  long double area = 0;         ///< A = ℓ − Σ ℓ of `subtracted`
  std::string source;           ///< "layer of 6 (2.9719e-02) − layer of 6 > 72 (7.853e-03)"
};

/// One transition probability per step, with its source.
struct MarkovTreeRate {
  int from = 0, to = -1;        ///< states (−1: the sea)
  long double perStep = 0;      ///< flux / area of `from`
  long double flux = 0;         ///< the barrier's flux
  long double area = 0;         ///< the area of `from`
  int fluxNode = 0;             ///< the atlas node whose flux it is
  std::string source;           ///< "flux of 6 > 72 (8.377e-07) / area of 6 (2.187e-02)"
};

/// A node left out of the tree as a barrier, lumped into a state.
struct MarkovTreeLumped {
  int node = 0;
  std::string path;
  std::string reason;           ///< the atlas's failure, or "inside 29, which has no flux"
  int state = 0;                ///< the state whose region holds it
};

struct MarkovTree {
  std::vector<MarkovTreeState> states;  ///< states[0]: the top, inside the centre's loop
  std::vector<MarkovTreeRate> rates;    ///< two per barrier (one at the top: to the sea)
  std::vector<MarkovTreeLumped> lumped;
  int levels = 0;                       ///< 1 + the deepest level among the states
  long double entryFlux = 0;            ///< Φ_centre: the loop's flux, the visits' entry
  long double residence = 0;            ///< ℓ_centre / Φ_centre: the mean visit (Kac)
  long double boxArea = 0;              ///< L² of the atlas's box (appendix A's b₀) to 12 digits: the largest b₂
};

/// Why `atlas` cannot make a tree, one wording for every front end (markovTreeFromAtlas throws it): empty, stopped
/// before the end (nodes not measured), no flux through the centre's loop, a non-positive or non-finite flux or
/// layer; nothing when it can (the nesting of the zones is checked while the tree is built).
[[nodiscard]] std::optional<std::string> markovTreeAtlasError(const Atlas& atlas);

/// Which barriers the tree takes (issue 50's ablation: the reach with and without each ingredient).  Left out, an
/// inner separatrix or a cantorus merges the two states it divides; a level above maxLevel is lumped.
struct MarkovTreeOptions {
  bool innerSeparatrices = true;
  bool cantori = true;
  int maxLevel = kMaxAtlasDepth;  ///< chains of a deeper atlas level are lumped into the state around them
};

/// The tree of `atlas`.  Throws std::invalid_argument with a clear message when the atlas cannot make one: empty,
/// stopped before the end (nodes not measured), no flux through the centre's loop, a non-positive or non-finite
/// flux or layer, chains about one island whose zones do not nest as their rotations say, a state of area ≤ 0.
[[nodiscard]] MarkovTree markovTreeFromAtlas(const Atlas& atlas, const MarkovTreeOptions& options = {});

/// The substochastic matrix M (row i: where state i goes), M[i][i] = 1 − Σ of its rates (the sea included).
[[nodiscard]] std::vector<std::vector<long double>> markovTreeMatrix(const MarkovTree& tree);

/// The rules of the model's entry (issue 54), one wording for every front end: α, the run's mean segment length, is
/// finite and at least one step; b₂, the stochastic area, lies in (0, L²] (it is part of the box, b₀ = L²); and
/// P₁ = w S(1), the model's probability that a segment lasts beyond one step, is at most 1 (w = α Φ_centre / b₂ and
/// S(1) = 1 − Φ_centre / A_top: a larger w is more visits per segment than a segment has steps to make).  Without a
/// tree (the request's check, before an atlas is read) only the first two, b₂ bounded by nothing but 0.  The first
/// rule broken, naming "alpha" and "b2", or nothing.
[[nodiscard]] std::optional<std::string> markovTreeEntryError(double alpha, double b2,
                                                              const MarkovTree* tree = nullptr);

/// The entry weight w = α Φ_centre / b₂ (visits to the loop's zone per segment of the run process): α the run's mean
/// segment length in steps, b₂ its stochastic area.  Throws std::invalid_argument with markovTreeEntryError's words
/// when the entry breaks its rules.
[[nodiscard]] long double markovTreeEntryWeight(const MarkovTree& tree, double alpha, double b2);

struct MarkovTreeSurvival {
  std::vector<std::uint64_t> t;                 ///< steps
  std::vector<long double> S;                   ///< e_top Mᵗ 1: a visit still inside the loop's zone after t steps
  std::vector<std::vector<long double>> state;  ///< [state][i]: the part of S(t_i) in that state
  std::vector<std::vector<long double>> level;  ///< [level][i]: summed over the states of an atlas level
  long double meanVisit = 0;                    ///< Σ_{t≥0} S(t) = e_top (I − M)⁻¹ 1, solved (Kac: the residence)
};

/// The largest t the survival is computed at.
inline constexpr std::uint64_t kMarkovTreeMaxT = std::uint64_t{1} << 62;

/// Up to this t the survival is t products of a vector with the sparse M in quad (exact; O(t n)), beyond it the modes.
inline constexpr std::uint64_t kMarkovTreeDirectSteps = 1024;

/// What markovTreeSurvival() of n states at m times costs: the bytes it holds (the eigenvectors, n² long doubles, and
/// each state's part at each t, n m) and about how many operations it takes (10 n³ + 2 n² m).
struct MarkovTreeCost {
  std::size_t states = 0, times = 0;
  long double bytes = 0, operations = 0;
};
[[nodiscard]] MarkovTreeCost markovTreeCost(std::size_t states, std::size_t times);
/// The refusal of a cost past core/limits (limits::kMarkovTreeStates states, limits::kMarkovTreeValues values n m),
/// naming the cost, or nothing.
[[nodiscard]] std::optional<std::string> markovTreeCostError(const MarkovTreeCost& cost);

/// S(t) and where it sits at each t of `t` (ascending or not; each at most kMarkovTreeMaxT), and the mean visit
/// (exact: an elimination in quad along the tree).  Throws std::invalid_argument for a t beyond that or a cost past
/// the limits (markovTreeCostError, before any work), OperationStopped (core/periodic) when `stop` is requested: it
/// is checked at least once per row of the decomposition and per t, a few milliseconds apart at the limit.
[[nodiscard]] MarkovTreeSurvival markovTreeSurvival(const MarkovTree& tree, const std::vector<std::uint64_t>& t,
                                                    std::stop_token stop = {});

/// The default grid: 0 and every distinct ⌈10^(k/perDecade)⌉ up to the first at or above tMax.  Throws
/// std::invalid_argument unless 1 ≤ tMax ≤ 10¹⁸ and 1 ≤ perDecade ≤ 1000.
[[nodiscard]] std::vector<std::uint64_t> markovTreeGrid(double tMax, int perDecade = 30);

/// γ(t) of the model: fitLogSlope() of S (or P = w S: the same) over runningExponentWindows(tEnd, lowest), the
/// statistics' one definition (core/stats/LogFits.hpp): decades ending at tEnd·10^(−k/2) (the tail sampler's windows
/// when tEnd is its last level).  S is fitted as a double: where it is below the smallest double (an exponential
/// tail, S < 10⁻³⁰⁸) the points are left out, and a window with fewer than 3 grid points has no γ.
struct MarkovTreeExponent {
  double from = 0, to = 0, gamma = 0;
};
[[nodiscard]] std::vector<MarkovTreeExponent> markovTreeExponents(const MarkovTreeSurvival& s, double lowest,
                                                                  double tEnd);

/// One measured level set against the tree: the tail sampler's P_t with its error, and the model's w S(t).
struct MarkovTreeLevelComparison {
  double t = 0;                 ///< steps
  double measured = 0, measuredError = 0;
  long double model = 0;        ///< w S(t) (below 10⁻³⁰⁸ where S decays exponentially: long double keeps it)
  long double ratio = 0;        ///< model / measured
  int holdingLevel = -1;        ///< the atlas level holding the largest part of the model's survivors at t
  double holdingShare = 0;      ///< that part of S(t)
};
/// The tree against a measured tail (issue 40's comparison: the report's item, `markov-tree --tail`, the docs' tables).
struct MarkovTreeComparison {
  std::vector<MarkovTreeLevelComparison> levels;  ///< the tail's reliable levels with P > 0 and t ≥ `from`
  long double weight = 0;       ///< w: visits per segment (markovTreeEntryWeight)
  double factor = 0;            ///< the agreement asked for
  double reach = 0;             ///< the largest t of `levels` whose ratio lies in [1/factor, factor] (0: none) —
                                ///< the last level the tree still holds at, whatever dips lie before it (at K = 0.15
                                ///< one level at 4.7·10⁴ is off by 0.32 and the next seven within 0.37–0.79)
};
/// The factor within which the report counts the tree as holding (a factor of 3 either way: at K = 0.1 the depth-2
/// tree stays within 0.39–1.38 of the sampler from 10³ to 10⁶ steps and falls to 0.105 at 2·10⁶, docs/markov-tree.md).
inline constexpr double kMarkovTreeAgreementFactor = 3;
/// The first t compared: P_t = w S(t) holds for t well above the sea's time scale (a visit's ~30 steps), and the tail
/// sampler's first level is the lowest at or above 10³ steps by default.
inline constexpr double kMarkovTreeCompareFrom = 1e3;
/// The model at each reliable level of `tail` from `from` steps on (α, b₂ as markovTreeEntryWeight: the run process's
/// mean segment length and stochastic area at the atlas's map).  Throws std::invalid_argument for α or b₂ not finite
/// and > 0, `from` or `factor` not finite, factor < 1.
[[nodiscard]] MarkovTreeComparison compareMarkovTreeWithTail(const MarkovTree& tree, double alpha, double b2,
                                                             const TailResult& tail,
                                                             double from = kMarkovTreeCompareFrom,
                                                             double factor = kMarkovTreeAgreementFactor,
                                                             std::stop_token stop = {});

/// One variant of the tree against the tail (issue 50's ablation): which barriers it takes, its states and reach.
struct MarkovTreeAblationRow {
  std::string variant;          ///< "every barrier", "no inner separatrices", "no cantori", "outer separatrices
                                ///< only", "levels <= L"
  MarkovTreeOptions options;
  std::size_t states = 0;
  double reach = 0;             ///< compareMarkovTreeWithTail's reach (0: none)
  std::vector<long double> ratio;  ///< model / measured at each compared level (the full tree's levels)
};
/// The tree of `atlas` with every barrier, without inner separatrices, without cantori, with outer separatrices
/// only, and cut at each level above 0, each against `tail` (compareMarkovTreeWithTail with its defaults): which
/// ingredient carries which decade of the tail.  Throws as markovTreeFromAtlas and compareMarkovTreeWithTail.
[[nodiscard]] std::vector<MarkovTreeAblationRow> markovTreeAblation(const Atlas& atlas, double alpha, double b2,
                                                                    const TailResult& tail, std::stop_token stop = {});

}  // namespace archipelago
