#pragma once
/// \file Provenance.hpp
/// \brief Where an output came from, in one place that every writer uses (issue 42): the program and its
/// version, the git commit it was built from, the map (K, xmin, xmax) and a free list of parameters (the view, the
/// run, …).  PNG files carry the fields as tEXt chunks (core/io/Png.hpp; the GUI through QImage::setText), JSON
/// files as the object "provenance", CSV files as "# key: value" header lines.
///
/// The commit is `git rev-parse --short=12 HEAD` of the source tree when the program was built, with "-dirty"
/// when tracked files differed from it, or "unknown" outside a git checkout (cmake/GitCommit.cmake).

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/map/MapParameters.hpp"

namespace archipelago {

/// The version of project() in CMakeLists.txt, e.g. "0.1.0".
[[nodiscard]] std::string_view programVersion() noexcept;
/// The commit the program was built from: 12 hex digits, "-dirty" when the tree had changes, or "unknown".
[[nodiscard]] std::string_view programCommit() noexcept;
/// "archipelago 0.1.0 (commit 0123456789ab)": what a --version line, a report or a file header names.
[[nodiscard]] std::string programDescription();

/// Ordered key/value fields.  Keys are short ASCII words (a PNG keyword: 1–79 Latin-1 characters, no leading,
/// trailing or double space); values are single-line text.
struct Provenance {
  std::vector<std::pair<std::string, std::string>> fields;

  /// Appends a field (a value given as a number is written as its shortest exact decimal text).
  Provenance& add(std::string key, std::string value);
  Provenance& add(std::string key, double value);
  Provenance& add(std::string key, long double value);
  /// The value of `key`, or nothing.
  [[nodiscard]] const std::string* find(std::string_view key) const;
};

/// Software ("archipelago 0.1.0"), Version, Commit: the fields of every output.
[[nodiscard]] Provenance programProvenance();
/// programProvenance() and the map: Map ("Q* of Karney (1983)"), K, xmin, xmax.
[[nodiscard]] Provenance mapProvenance(const MapParameters& map);

/// The shortest decimal text that reads back as exactly `v` (long double: a deep view's edges).
[[nodiscard]] std::string shortestDecimal(long double v);

}  // namespace archipelago
