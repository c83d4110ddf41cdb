#pragma once
/// \file ReportRuns.hpp
/// \brief The runs of the reproduction report and their sizes, read from the presets (resources/presets, issue #24:
/// the fig. 6 size was once written in a preset and again, with another seed, in the report).
///
///   k01        fig. 6 and 7 at K = 0.1: full — the preset k0.1-paper-fig6 (the paper's M = 1600 orbits of 2·10⁹
///              steps); quick — the preset k0.1-minute with T/40 and M/2 (5·10⁸ steps, seconds)
///   k01 short  its q = 1 companion (the preset's "companion" fraction; issue #26): the short times of S_t, D_t
///   fig. 3     the presets small-k-negative, -zero, -positive (full), with T/10 (quick)
///   decay      K = 10⁻³ and 10⁻² (§4: "similar agreement"): the small-k-positive preset at that K in the box
///              ±5√K (the preset's box is ±5√K at K = 10⁻⁴: the island of width 3√K inside, the same shape)
///   K scan     §5's 26 K (core/scan), q = 16, M = 64, T = 2·10⁵ (quick) or 5·10⁶ (full), seed 1983
///   tail scan  the tail sampler at K in its working range, 0.05–0.25 (core/tail/TailScan.hpp; issue 55, item
///              tail-gamma-K), to t_max = 10⁶ steps: full — 21 K, 0.05:0.25:0.01, N = 800, R = 16; quick — K = 0.1,
///              0.15, 0.2, N = 400, R = 8 (the fewest walkers that reach 10⁶ reliably at those K); folder
///              "tailscan-SIZE", a tail file per K
///   atlas      the islands around islands of the k01 run's map (core/atlas) for the Markov tree: depth 1 (quick,
///              seconds) or 2 (full, minutes), file "atlas-SIZE.json"
/// Run files are kept in OUTDIR/runs under the names below, so that a report resumes and reuses them.

#include <filesystem>
#include <string>

#include "core/atlas/Atlas.hpp"
#include "core/stochasticarea/StochasticArea.hpp"
#include "core/scan/ScanRun.hpp"
#include "core/tail/TailSampler.hpp"
#include "core/tail/TailScan.hpp"
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago::report {

enum class ReportSize { quick, full };

[[nodiscard]] const char* sizeName(ReportSize size) noexcept;  ///< "quick", "full"

/// One run of the report: its parameters, its file under OUTDIR/runs, and the archipelago-cli command that makes it.
struct ReportRun {
  TrappingParameters params;
  std::string file;
  std::string command;
};

/// The K = 0.1 run of figs. 6–7.
[[nodiscard]] ReportRun k01Run(ReportSize size);
/// Its q = 1 companion (companionParameters with the preset's fraction), file "k01-SIZE.short.json".
[[nodiscard]] ReportRun k01CompanionRun(ReportSize size);
/// The tail sampler's request for the K = 0.1 run's process (issue #29): quick N = 100, R = 8 to 10⁶ steps (about
/// a second), full N = 800, R = 16 to 10⁷ (9·10¹⁰ steps, docs/tail.md).
[[nodiscard]] TailRequest tailSamplerRequest(ReportSize size);
/// Its command line, for the item and the figure.
[[nodiscard]] std::string tailSamplerCommand(ReportSize size);
/// The atlas of the K = 0.1 run's map (its K and box), for the markov-tree item: depth 1 (quick) or 2 (full).
[[nodiscard]] AtlasRequest k01AtlasRequest(ReportSize size);
/// Its file under OUTDIR/runs: "atlas-SIZE.json".
[[nodiscard]] std::string k01AtlasFile(ReportSize size);
/// The commands that make the markov-tree item alone: the atlas, the tail (tailSamplerCommand) and markov-tree with
/// the run's α and b₂.
[[nodiscard]] std::string markovTreeCommand(ReportSize size, double alpha, double b2);
/// The small-K run of fig. 3, panel 'a' (K = −10⁻⁴), 'b' (0) or 'c' (10⁻⁴).
[[nodiscard]] ReportRun smallKRun(char panel, ReportSize size);
/// A run at K = 10⁻³ or 10⁻² for §4's "similar agreement" (the K = 10⁻⁴ run is smallKRun('c')).
[[nodiscard]] ReportRun decayRun(double K, ReportSize size);

/// §5's K scan in `dir`, and the command that makes it.
[[nodiscard]] KScanRequest kScanRequest(ReportSize size, const std::filesystem::path& dir);
[[nodiscard]] std::string kScanCommand(ReportSize size);

/// The tail sampler over K in `dir` (the tail's default process in each K's scan box, seed 1), and the command that
/// makes it.
[[nodiscard]] TailScanRequest tailScanRequest(ReportSize size, const std::filesystem::path& dir);
[[nodiscard]] std::string tailScanCommand(ReportSize size);

/// b₂ (§5, an area) of `box` at K = 0.1: 2²⁷ (quick) or 2³⁰ (full) steps of box counting on 1024² boxes.
[[nodiscard]] StochasticAreaRequest stochasticAreaRequest(ReportSize size, const MapParameters& box);
/// A box of the paper's size for b₂ (issue #26): side L = 1, (−0.7, 0.3), since the paper's b₂ = 0.693 needs
/// b₀ = L² ≥ 0.693 and its box is not in our copy.
[[nodiscard]] MapParameters paperSizedBox();

/// "archipelago-cli " + rest.
[[nodiscard]] std::string cliCommand(const std::string& rest);
/// "archipelago-reproduce --only ID OUTDIR": the statements no single archipelago-cli command reproduces.
[[nodiscard]] std::string onlyCommand(std::string_view id);

}  // namespace archipelago::report
