#pragma once
/// \file AtlasExport.hpp
/// \brief The atlas as JSON (the whole tree, with its request and provenance) and as CSV (one row per island, with
/// its parent): what `archipelago-cli atlas --json/--csv` writes and Python's atlas() returns.

#include <filesystem>
#include <string>

#include "core/atlas/Atlas.hpp"

namespace archipelago {

/// The JSON text: {"format": "archipelago atlas", "program", "provenance", "map", "request", "cancelled", "seconds",
/// "nodes": [...]} (docs/atlas.md lists the fields of a node).
[[nodiscard]] std::string atlasJson(const Atlas& atlas);

/// The CSV text: "# key: value" provenance lines, then the header and one row per node (docs/atlas.md).
[[nodiscard]] std::string atlasCsv(const Atlas& atlas);

/// The same, written atomically (io::writeFileAtomically); throws std::runtime_error naming the file on failure.
void writeAtlasJson(const std::filesystem::path& path, const Atlas& atlas);
void writeAtlasCsv(const std::filesystem::path& path, const Atlas& atlas);

}  // namespace archipelago
