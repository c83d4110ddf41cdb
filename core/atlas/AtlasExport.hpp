#pragma once
/// \file AtlasExport.hpp
/// \brief The atlas as JSON (the whole tree, with its request and provenance) and as CSV (one row per island, with
/// its parent): what `archipelago-cli atlas --json/--csv` writes and Python's atlas() returns; and the JSON read back
/// (a session keeps its atlas this way, core/session).

#include <filesystem>
#include <string>

#include "core/atlas/Atlas.hpp"

namespace archipelago {

/// The JSON text: {"format": "archipelago atlas", "format_version": 2, "program", "provenance", "map", "request",
/// "cancelled", "seconds", "nodes": [...], "checksum": "sha256:…"} (docs/atlas.md lists the fields of a node; the
/// checksum is io::jsonChecksum's, as run and tail files have: any edit is refused on load).
inline constexpr int kAtlasFormatVersion = 2;  ///< 2: signed (issue 54); files without a version are read unsigned
[[nodiscard]] std::string atlasJson(const Atlas& atlas);
[[nodiscard]] std::string atlasJson(const Atlas& atlas);

/// The CSV text: "# key: value" provenance lines, then the header and one row per node (docs/atlas.md).
[[nodiscard]] std::string atlasCsv(const Atlas& atlas);

/// The same, written atomically (io::writeFileAtomically); throws std::runtime_error naming the file on failure.
void writeAtlasJson(const std::filesystem::path& path, const Atlas& atlas);
void writeAtlasCsv(const std::filesystem::path& path, const Atlas& atlas);

/// The most islands an atlas document may list (a depth-6 tree of short periods stays far below).
inline constexpr std::size_t kMaxAtlasNodes = 1'000'000;

/// Reads atlasJson()'s text back, validated whole: the format's name, no unknown, missing or repeated key, the
/// request by validationError(AtlasRequest), every number finite and in its range (a null only where the writer
/// writes one for a non-finite value: a residue (NaN) and the flux's agreeing digits (all digits agree: infinity)),
/// and the tree's structure (node i at index i, parents before children, each level its parent's plus one, each
/// period its parent's times q of its p/q, children lists that match the parents).  Throws io::BadFile
/// (a std::runtime_error) naming the first bad key ("nodes[3].period = -1 must be …"); never anything else.
///
/// What the JSON does not keep is not invented: a node's `orbit` holds its centre as its one point (with its period,
/// residue and symmetry line) and a flux's `partner` the point written (with its residue); refinePeriodicOrbit() finds
/// either whole again from that point.  Long doubles come back as the doubles written, so atlasJson() of the result
/// is the text read, except `islands_area` (derived: period × area), which may differ in its last digit from a text
/// written from the long doubles of a computed atlas (and is identical from then on).  `program`, `provenance` and
/// `path` are checked for their type only: atlasJson() writes them anew.
[[nodiscard]] Atlas atlasFromJson(const std::string& text);

}  // namespace archipelago
