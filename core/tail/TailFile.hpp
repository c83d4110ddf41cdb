#pragma once
/// \file TailFile.hpp
/// \brief Tail files: a sampler run (TailSampler.hpp) and its results as one versioned, checksummed JSON
/// document, resumable bit for bit; and the CSV of its levels.
///
/// Format "archipelago-tail", version 1:
///
///     {"format": "archipelago-tail", "version": 1, "program": "archipelago 0.1.0 (commit 0123456789ab)",
///      "parameters": {…the run spec's parameters…}, "coefficients": {"A", "B", "C", "m"},
///      "sampler": {"population", "replicas", "first", "t_max", "level_bins", "epsilon", "clones",
///                  "metropolis_steps", "warmup", "min_ancestors"},
///      "level_blocks": [L_0, L_1, …],
///      "finished": bool, "steps": total map steps, "elapsedSeconds": s, "kernel": "…",
///      "levels": [{"t", "P", "P_error", "survivors", "ancestors", "reliable", "fewest_ancestors", "population",
///                  "P_replicas", "steps", "acceptance"}, …],
///      "exponents": [{"t", "t_from", "t_to", "gamma", "gamma_error"}, …],
///      "state": {"next", "age", "first_replica", "pilot": {"orbits", "trials", "successes"}, "entry_orbits", "steps_at_level",
///                "replicas": [{"orbits_done", "trials", "levels": [[population, survivors, ancestors, proposals,
///                accepted], …], "walkers": [[X, Y, block, draws, length, X₀, Y₀, block₀, draws₀, ancestor, alive],
///                …], "alive": bool}, …]},
///      "checksum": "sha256:…"}
///
/// A slice of a distributed run (TailSampler.hpp, "slice") holds the replicas [first_replica, first_replica +
/// its replicas' count) of "sampler"'s R; its "levels" are those of its own replicas.  "first_replica" is absent
/// from files written before slices existed (they hold every replica from 0).
/// "levels" and "exponents" are TailResult.hpp's, written for readers (a NaN is null) and recomputed from the state
/// when read.  Integers are JSON integers (exact); the checksum is that of RunFile.hpp (SHA-256 of the document
/// without it, as dumped), so that an edit is detected.  Read with io::parseJson (depth-limited, strict); the
/// state is validated whole (tailStateError()) before it is used.  Written atomically (io::writeFileAtomically).

#include <filesystem>
#include <string>

#include "core/tail/TailResult.hpp"

namespace archipelago {

inline constexpr const char* kTailFileFormatName = "archipelago-tail";
inline constexpr int kTailFileFormatVersion = 1;
/// The largest tail file read: 16 million walkers of ~200 bytes.
inline constexpr std::uintmax_t kMaxTailFileBytes = std::uintmax_t{4} << 30;

/// The JSON text of a tail file.
[[nodiscard]] std::string tailFileText(const TailState& state);
/// Parses and validates tail-file text.  Throws io::BadFile (a std::runtime_error) with one line for anything wrong (not JSON,
/// another format or version, a checksum that does not match, a field missing or of the wrong type, a request
/// out of range, levels or coefficients this program would not derive, an inconsistent state).
[[nodiscard]] TailState parseTailFile(const std::string& text);

/// Whether `path` is a JSON document of format "archipelago-tail" (whatever else it holds); false for anything
/// else, unreadable included (the reader of the other format then says what is wrong).
[[nodiscard]] bool isTailFile(const std::filesystem::path& path);

/// Writes atomically.  Throws std::runtime_error naming the path.
void saveTailFile(const std::filesystem::path& path, const TailState& state);
/// Reads and validates.  Throws std::runtime_error naming the path (io::BadFile for a file refused for its content).
[[nodiscard]] TailState loadTailFile(const std::filesystem::path& path);

/// The CSV of the levels: a "# key: value" header (the process, the sampler's settings, the steps) and
/// t,P,P_error,survivors,ancestors,fewest_ancestors,reliable,steps, then the running exponent in its own table
/// (t,t_from,t_to,gamma,gamma_error) after a blank line.
[[nodiscard]] std::string tailCsvText(const TailState& state, const TailResult& result);

}  // namespace archipelago
