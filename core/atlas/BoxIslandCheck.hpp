#pragma once
/// \file BoxIslandCheck.hpp
/// \brief The box of a trapping run checked against the central island (issue 39, deliverable 4): whether the
/// randomizing zone 0 ≤ X ≤ Xr reaches into the island's boundary circle or the separatrix loop around it, or the box
/// [xmin, xmax) × [−L/2, L/2) cuts them, which and by how much.
///
/// Appendix B's process randomizes y wherever an orbit enters the zone; the paper's process is that of Q only when
/// the zone lies in the sea and the box holds the island (appendix B: xmin < −√K is the least of it).  When the zone
/// cuts the island, orbits of the island are randomized and the island's stickiness is not the paper's: `run --K 0.3`
/// with the default box (−0.8, 0.5) gave a longest segment of 192 steps (issue 39; 176 in the default spec's 10⁹ steps
/// here, 7456 in the K scan's box: docs/cli.md).  The check is the one every front end
/// shows (the CLI's run and tail, the GUI, Python): one message, core's.
///
/// Two regions are checked.  (1) The island itself, its **boundary circle**, found by the atlas's own method on one
/// ray at a coarse resolution (centralBoundaryCircle, Atlas.hpp: its steps 1–2, one classifier): 64 points of the
/// symmetry line S₂ (y = 0) from the elliptic fixed point (−√K, 0) out to −2√K are classified by their rotation
/// number about the centre (T = kDefaultIterations per block, in the box of the K scan's rule, scanBox(K), so that
/// the island is measured on Q, not on the run's Q*): a circle is regular with no rational p/q (q ≤ 2000) within its
/// accuracy.  The outermost circle point is bisected 16 times against its outer neighbour and proven (its polygon
/// converges, its rotation measured again names no rational; else the next circle inwards is tried: a sticky chaotic
/// orbit that passed for regular took the check's own classifier to x = 0.021 at K = 0.15, where the circle ends near
/// −0.08), and that circle's polygon (8192 points of its orbit under Q) gives its extent: its smallest and largest x
/// and its largest |y|.  Resolution √K/64/2¹⁶ in x.  A zone or box that cuts the circle randomizes or wraps orbits
/// of the island itself.  (2) The **separatrix loop** of the hyperbolic fixed point (√K, 0) around the
/// island, −2√K ≤ x ≤ √K (eq. hamb at small K; the K scan's box rule, ScanBox.hpp, holds it with a margin of 0.2): the
/// island's chains and sticky layer lie between the circle and the loop, and a zone that reaches into the loop
/// randomizes orbits trapped there.  At K = 0.3 in the default box it is (2) that is cut: the zone's edge x = −0.774
/// lies 0.32 inside the loop and only 0.002 outside the boundary circle (whose left tip is at −0.772), so every orbit
/// circling the island outside its last circle passes through the zone within a turn.  The loop's extent is the small-K
/// formula, not measured: at larger K its far crossing moves, so a cut of the loop by less than a few 10⁻³ is a
/// borderline case.  Cost: about 2·10⁶ steps of Q (tens of milliseconds: 50 ms a check on two busy cores).

#include <optional>
#include <string>

#include "core/map/MapParameters.hpp"

namespace archipelago {

/// The central island's boundary circle as the check measures it.
struct CentralIslandExtent {
  bool found = false;        ///< false for K ≤ 0 or K ≥ 1 (no elliptic fixed point) or no circle at the scan's resolution
  double K = 0;
  double xLeft = 0;          ///< the circle's smallest x
  double xRight = 0;         ///< its largest x
  double yMax = 0;           ///< its largest |y|
  double crossing = 0;       ///< x where it crosses S₂ (y = 0) left of the centre
  double rotation = 0;       ///< its rotation number about (−√K, 0), turns per step
};

/// The result of the check: the island, how far the zone and the box cut it (0 or less: not at all), and the message.
struct BoxIslandCheck {
  CentralIslandExtent island;
  double zoneEdge = 0;       ///< x of the randomizing zone's right edge: xmin + Xr·L
  double zoneDepth = 0;      ///< zoneEdge − island.xLeft: how far the zone reaches into the circle (> 0: it does)
  double cutLeft = 0;        ///< xmin − island.xLeft (> 0: the box's left edge cuts the circle)
  double cutRight = 0;       ///< island.xRight − xmax (> 0: the right edge cuts it)
  double cutY = 0;           ///< island.yMax − L/2 (> 0: the box's height cuts it)
  double loopLeft = 0;       ///< −2√K: the separatrix loop's far crossing of y = 0 (eq. hamb; ScanBox.hpp's rule)
  double loopRight = 0;      ///< √K: the hyperbolic fixed point that closes the loop
  double loopDepth = 0;      ///< zoneEdge − loopLeft: how far the zone reaches into the loop (> 0: it does)
  double loopCutRight = 0;   ///< √K − xmax (> 0: the box's right edge lies inside the loop)
  std::string warning;       ///< empty when the box holds the loop and the zone misses it; else one paragraph

  [[nodiscard]] bool cuts() const noexcept { return !warning.empty(); }
};

/// Checks the box `map` and the randomizing zone's width Xr (unit coordinates, TrappingParameters::Xr) against the
/// central island of Q at map.K.  The warning names what is cut (the circle or the loop; by the zone, the box's left or
/// right edge, its height), by how much in x (or y), and the extents, so that a person can choose a box that holds it.  Depends only on
/// the values (the island of a K is measured afresh each call: tens of milliseconds).  Invalid maps (validationError)
/// and K outside (0, 1) give no warning: the first are refused by the parameters' rules, the second have no island.
[[nodiscard]] BoxIslandCheck checkBoxAgainstIsland(const MapParameters& map, double Xr);

/// The atlas's rule (issue 50): the atlas maps the central island of Q and its chains out to the separatrix loop, so
/// its box must hold both, or their orbits wrap round the box and the circles and chains found are not Q's.  At
/// K = 0.22 in the default box (−0.8, 0.5) the centre's "boundary circle" had an area of 0.33445 (its point on the
/// box's edge) against Q's 0.40059 (scripts/atlas-validate.py), and its 2/9 chain was not followed; in the K scan's
/// box both hold the independent values.  Nothing when the box holds the circle (checkBoxAgainstIsland's cutLeft,
/// cutRight, cutY) and the loop (loopDepth with no zone, loopCutRight); else why, naming the K scan's box, which
/// holds them.  computeAtlas refuses such a box.  K outside (0, 1) and invalid maps give nothing (validationError's).
[[nodiscard]] std::optional<std::string> atlasBoxError(const MapParameters& map);

}  // namespace archipelago
