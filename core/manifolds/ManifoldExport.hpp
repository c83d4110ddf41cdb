#pragma once
/// \file ManifoldExport.hpp
/// \brief The files of core/manifolds, one definition for every front end: a branch as CSV, the flux (and the Kac
/// check) as JSON.
///
/// CSV of a branch (ManifoldCurve.hpp): '# key: value' metadata lines carrying every parameter of the request and
/// what was computed (the orbit point, λ, the map, the bounds, points, pieces, why it stopped), then the header
/// "s,x,y" and one row per point: s the arc length from the orbit point (physical units), x, y physical, 19
/// significant digits (long double).  The polyline is cut where the branch escapes or wraps (ManifoldCurve.hpp):
/// each further piece starts after a line "# piece k" (k = 2, 3, …), which CSV readers that skip '#' lines ignore
/// (numpy.loadtxt, pandas comment='#'); s does not advance across a cut.
///
/// JSON of the flux (TurnstileFlux.hpp): the orbit, the two primary points with their actions, the lobe area by both
/// methods with the polygon's error and the agreeing digits, the zone area by both, and the Kac check when run.
/// Numbers are JSON doubles (17 significant digits); the actions are also given as 34-digit text.

#include <filesystem>
#include <ostream>
#include <string>

#include "core/manifolds/KacCheck.hpp"
#include "core/manifolds/ManifoldCurve.hpp"
#include "core/manifolds/QuadText.hpp"  // quadText, quadCoordinateText: the actions and points its files write
#include "core/manifolds/TurnstileFlux.hpp"

namespace archipelago {

/// Writes the CSV described above to `out`.
void writeManifoldCsv(std::ostream& out, const ManifoldCurveRequest& request, const ManifoldCurve& curve);
/// The same into `path`, atomically (io::AtomicOutputFile).  Throws std::runtime_error naming the path on failure.
void writeManifoldCsv(const std::filesystem::path& path, const ManifoldCurveRequest& request, const ManifoldCurve& curve);

/// The flux as JSON text (one object; `kac` and `kacResult` may be null).
[[nodiscard]] std::string turnstileJson(const TurnstileRequest& request, const TurnstileFlux& flux,
                                        const KacRequest* kac = nullptr, const KacResult* kacResult = nullptr,
                                        double seconds = -1);

}  // namespace archipelago
