#pragma once
/// \file SessionFile.hpp
/// \brief A session file (`.archipelago`): everything the window shows, as one JSON document, so that opening it
/// restores the window as it was.
///
/// One codec, strict like the run spec's (core/runspec): unknown or repeated keys, wrong types, non-finite numbers,
/// empty or inverted rectangles, unknown portrait modes or colour maps and oversized lists are errors naming the
/// key; a file is parsed and validated whole before anything is applied, so a bad or foreign file changes
/// nothing.  The parameters are a run spec (core/runspec's codec); the run is either referenced (a run file's path,
/// relative to the session file when it was saved beside it) or embedded (the run file's own document, with its
/// checksum, read back through core/runfile's validation).  Reading is bounded (io::readRegularFile) and writing
/// atomic (io::writeFileAtomically).
///
///   {"format": "archipelago-session", "version": 1,
///    "spec": {…run spec…},
///    "run": null | {"file": "run.json"} | {"embedded": {…run file…}},  (either may add "stopped": true)
///    "tab": "Phase portrait",
///    "portrait": {"history": [{"centre": [X, Y], "size": ["w", "h"]}, …], "current": 0, "mode": "density",
///                 "colours": "inferno", "budget": 100000000,
///                 "orbits": [{"start": [x, y], "steps": 20000, "backward": false, "number": 1}, …],
///                 "periodic": [{"label": "7/20", "points": [[x, y], …]}, …],
///                 "manifolds": {"orbit": null | [[x, y], …]}},   (only when the manifolds are shown)
///    "segment": {"rank": 0, "position": 1234},
///    "plots": [{"name": "f_t", "zoom": [xmin, xmax, ymin, ymax]}, …],
///    "atlas": {…atlas…},   (only when the window holds one)
///    "markovTree": {"alpha": α, "b2": b₂},   (only with the atlas: its Markov tree's P_t was drawn)
///    "tail": {"file": "tail.json"},   (only when a tail estimate was drawn on P_t)
///    "sidePage": "Atlas"}   (the page beside the portrait: Run, Orbits, Manifolds, Profile, Atlas)
///
/// A launched orbit keeps its steps, direction and number (the number is its colour; issue 53, finding 2: sessions
/// before kept only the start, `[x, y]`, and reopened 100 000 steps backward as 20 000 forward, renumbered and
/// recoloured).  That old entry is still read: kSessionOrbitSteps forward, numbered in order.
///
/// The atlas of the islands (issue 38, the Atlas page) is core/atlas's document as atlasJson() writes it, read back by
/// atlasFromJson() (no recomputation); it must be of the session's map (its K and box), else the session is refused.
///
/// The Markov tree of that atlas and the tail estimate drawn on P_t are kept by their inputs, not their curves (issue
/// 53, finding 3: both were lost): the model's α and b₂ (computed again on opening, in the background: cheap), the
/// tail file's path (read again; relative to the session file when it was saved beside it, as the run file's).  A
/// tail file that is gone does not refuse the session: reading it again says so.  Sessions without these keys (and
/// without "sidePage") are read as before.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/atlas/Atlas.hpp"
#include "core/colour/ColourMap.hpp"
#include "core/portrait/PortraitRaster.hpp"
#include "core/view/Viewport.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/runspec/RunSpec.hpp"

namespace archipelago {

inline constexpr const char* kSessionFormatName = "archipelago-session";
inline constexpr int kSessionFormatVersion = 1;
inline constexpr const char* kSessionFileSuffix = ".archipelago";
/// Bounds of what a session may hold (a bigger file is refused before it is read, a longer list is an error).
inline constexpr std::uintmax_t kMaxSessionFileBytes = std::uintmax_t{2} << 30;  ///< an embedded run may be large
inline constexpr std::size_t kMaxSessionHistory = 1000;
/// Launched orbits: the GUI's own bound too (PortraitController refuses more), so that every orbit a session
/// can hold is drawn and measured: 500 orbits of 20 000 steps are 10⁷ points (160 MB drawn), and each is
/// measured once in the background (issue #23, finding 5: 10⁴ orbits once froze the GUI for an hour).
inline constexpr std::size_t kMaxSessionOrbits = 500;
/// Steps of a launched orbit whose entry does not say (an old session's `[x, y]`): the GUI's default too.
inline constexpr std::uint64_t kSessionOrbitSteps = 20000;
/// Numbers of launched orbits lie in [1, kMaxSessionOrbitNumber] (exact in a JSON double) and are distinct.
inline constexpr std::uint64_t kMaxSessionOrbitNumber = std::uint64_t{1} << 53;
inline constexpr std::size_t kMaxSessionPeriodicPoints = 1'000'000;  ///< over all periodic overlays
inline constexpr std::size_t kMaxSessionPlots = 64;

/// Portrait views are exact (core/view/Viewport): the centre as integer grid units, the size in grid units as
/// a decimal string of 21 significant digits (a long double's 64-bit mantissa round-trips), so a view 10⁻¹⁰ wide is
/// restored to the bit.  Each is checked by Viewport::fromUnits (inside the box, not below the resolution).
///
/// A rectangle of a plane: [xmin, xmax] × [ymin, ymax], finite, xmin < xmax, ymin < ymax.
struct SessionRect {
  double xmin = 0, xmax = 1, ymin = 0, ymax = 1;
  friend bool operator==(const SessionRect&, const SessionRect&) = default;
};

/// One launched orbit: as the Orbits page launched it.
struct SessionOrbit {
  std::array<double, 2> start{};                ///< physical (x, y)
  std::uint64_t steps = kSessionOrbitSteps;     ///< 1 … limits::kOrbitLength
  bool backward = false;                        ///< traced with N⁻¹
  std::uint64_t number = 0;                     ///< its number in the list, which picks its colour (0: the next)
  friend bool operator==(const SessionOrbit&, const SessionOrbit&) = default;
};

struct SessionPeriodicOverlay {
  std::string label;
  std::vector<std::array<double, 2>> points;
  friend bool operator==(const SessionPeriodicOverlay&, const SessionPeriodicOverlay&) = default;
};

struct SessionPortrait {
  std::vector<Viewport> history;                ///< zoom history, oldest first (empty: the whole box)
  std::size_t current = 0;                      ///< the view shown: history[current]
  PortraitMode mode = PortraitMode::Density;
  ColourMapName colours = ColourMapName::Inferno;
  std::uint64_t budget = 0;                     ///< points budget of deep zoom (0: the panel's default)
  std::vector<SessionOrbit> orbits;             ///< orbits the user launched, in order
  std::vector<SessionPeriodicOverlay> periodic;
  /// The manifolds layer (issue 37, finding 4): shown or not, and of which hyperbolic orbit — its points, period
  /// = their number (empty: the fixed point (√K, 0)).  Written only when shown ("manifolds": {"orbit": …}).
  bool manifolds = false;
  std::vector<std::array<double, 2>> manifoldOrbit;
  friend bool operator==(const SessionPortrait&, const SessionPortrait&) = default;
};

struct SessionPlotZoom {
  std::string name;                             ///< the plot's file name ("f_t", "P_t", …)
  SessionRect zoom;
  friend bool operator==(const SessionPlotZoom&, const SessionPlotZoom&) = default;
};

/// The inputs of the Markov tree's P_t = w S(t), w = α Φ_centre / b₂ (core/markovtree): positive and finite.
struct SessionMarkovTree {
  double alpha = 0;
  double b2 = 0;
  friend bool operator==(const SessionMarkovTree&, const SessionMarkovTree&) = default;
};

struct Session {
  RunSpec spec;
  std::optional<std::filesystem::path> runFile;  ///< a referenced run file (as written: relative or absolute)
  std::optional<TrappingState> embeddedRun;      ///< or the run itself
  bool runStopped = false;                       ///< the run was stopped (final: it opens stopped, not resumable)
  std::string tab;                               ///< the active tab's title ("" = the first)
  SessionPortrait portrait;
  int segmentRank = -1;                          ///< the selected long segment (−1: none)
  std::uint64_t segmentPosition = 0;             ///< its replay position (index of the current point)
  std::vector<SessionPlotZoom> plots;            ///< plots the user zoomed (others follow their data)
  std::optional<Atlas> atlas;                    ///< the atlas of the islands shown (of the session's map)
  std::optional<SessionMarkovTree> markovTree;   ///< its Markov tree's inputs (only with `atlas`)
  std::optional<std::filesystem::path> tailFile; ///< the tail estimate drawn on P_t (as written: relative or absolute)
  std::string sidePage;                          ///< the page beside the portrait, by its title ("" = as it is)
};

/// The document's text (embedding the run when `embeddedRun` is set).
[[nodiscard]] std::string sessionText(const Session& session);
/// Parses and validates a whole document.  Throws io::BadFile naming the first problem.
[[nodiscard]] Session parseSession(std::string_view text);
/// Writes atomically.  Throws std::runtime_error (with the path) when it cannot.
void saveSession(const std::filesystem::path& path, const Session& session);
/// Reads (bounded, regular files only), parses and validates; a referenced run file's relative path is
/// resolved against the session file's folder and must exist (a tail file's is resolved too, and may be gone).  Throws io::BadFile naming the file and the problem
/// (a file that cannot be read included).
[[nodiscard]] Session loadSession(const std::filesystem::path& path);

}  // namespace archipelago
