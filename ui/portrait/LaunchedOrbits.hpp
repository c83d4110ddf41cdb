#pragma once
/// \file LaunchedOrbits.hpp
/// \brief The orbits a user launched on the portrait (a click, a session), as immutable values.
///
/// Each launched orbit is computed once, off the GUI thread (PortraitController's background jobs): first its
/// points (core's traceOrbit, a few milliseconds), drawn as soon as they arrive, then its measures — the
/// rotation number about the centre with its digits and the island chain (core/measures' identifyChain, a few
/// tenths of a second; issue #27) — exactly as `archipelago-cli rotation --json` computes them for the same
/// start.  Earlier orbits are never recomputed (issue #23, finding 5).  No maths here.

#include <QColor>
#include <QMetaType>
#include <QPointF>
#include <QString>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/measures/ChainIdentification.hpp"
#include "core/session/SessionFile.hpp"

namespace archipelago::ui {

/// Steps of N drawn for a launched orbit.
inline constexpr std::uint64_t kLaunchedOrbitSteps = kSessionOrbitSteps;  // an old session's orbits have as many
/// At most this many launched orbits at once: the session file's bound (core/session), so every session opens
/// whole; with kLaunchedOrbitSteps each, the drawn points stay below 10⁷ (160 MB).
inline constexpr std::size_t kMaxLaunchedOrbits = kMaxSessionOrbits;

/// The measures of one orbit: core's request and answer (the numbers `archipelago-cli rotation --json` prints).
struct OrbitMeasuresResult {
  ChainRequest request;
  ChainIdentification chain;
  QString error;     ///< why there are none (e.g. the start lies outside the box); empty otherwise
  double seconds = 0;
};
using OrbitMeasuresPtr = std::shared_ptr<const OrbitMeasuresResult>;

struct LaunchedOrbit {
  quint64 id = 0;                 ///< its number: unique among the orbits shown (a session or Undo Clear brings it back)
  long double x = 0;              ///< the start as given (physical)
  long double y = 0;
  std::uint64_t steps = 0;
  bool backward = false;          ///< traced with N⁻¹ (its past); measured forward from the same start, like the CLI
  QColor colour;
  std::shared_ptr<const std::vector<QPointF>> points;  ///< null while computing
  OrbitMeasuresPtr measures;                           ///< null while measuring
  QString error;                                       ///< the orbit could not be computed
};

/// "1/6", "0.1900993 (14.2 digits)", "chaotic (3.1 digits)", … : the rotation column of the list.
[[nodiscard]] QString rotationText(const OrbitMeasuresResult& m);
/// The chain column: "6 × 23 = 138" or core's phrase ("invariant curve about the centre", "chaotic", …).
[[nodiscard]] QString chainText(const OrbitMeasuresResult& m);

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::ui::OrbitMeasuresPtr)
