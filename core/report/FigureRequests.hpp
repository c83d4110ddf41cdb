#pragma once
/// \file FigureRequests.hpp
/// \brief The portraits of the report's figures 1, 2 and 8b (docs/design.md, "Figures") and the level curves of fig. 4,
/// as requests to core's renderers, each with the archipelago-cli command that draws it alone.

#include <string>

#include "core/portrait/PortraitRenderer.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/report/ReportRuns.hpp"

namespace archipelago::report {

/// Fig. 1: the islands of Q at K = 0.1 (the central island, its chain of six, the islands around those): an
/// Orbits-mode portrait of the default box, x ∈ [−0.8, 0.5], y ∈ [−0.65, 0.65] (quick: 600², 2·10⁷ points; full:
/// 1200², 2·10⁸).
[[nodiscard]] PortraitRequest figureOneRequest(ReportSize size);
[[nodiscard]] std::string figureOneCommand(ReportSize size);

/// Fig. 2 (the paper's dark region: the chaotic sea of Q*, its holes the islands): a Density-mode portrait, (a) of
/// the whole default box, (b) the enlargement around the 138-chain's member.
[[nodiscard]] PortraitRequest figureTwoRequest(ReportSize size, bool enlargement);
[[nodiscard]] std::string figureTwoCommand(ReportSize size, bool enlargement);

/// Fig. 8b when no recorded segment sticks to the 138-chain: orbits from a grid of seeds near its member.
[[nodiscard]] PortraitRequest chain138NeighbourhoodRequest(ReportSize size);

/// Fig. 4: the small-K Hamiltonians in scaled variables, H = ½Y² − ⅔X³ + s·2X with s = 0 (K = 0, eq. ham, panel a)
/// and s = +1 (K > 0, eq. hamb, panel b) (core/theory/SmallKTheory.hpp's file comment).
[[nodiscard]] double smallKHamiltonian(double X, double Y, int sign) noexcept;

/// The text chunks of a figure that is neither a picture of the map's plane (portraitProvenance, longOrbitProvenance)
/// nor a run's statistic (runProvenance): the program, the image and, when it has one, the command that computes it.
[[nodiscard]] Provenance figureProvenance(const std::string& image, const std::string& command = {});
/// Fig. 4's panel of `sign` (s = 0: a, s = +1: b): figureProvenance's, the Hamiltonian and its scaled view (X, Y).
[[nodiscard]] Provenance levelCurveProvenance(int sign, const PhysicalRect& view);

}  // namespace archipelago::report
