#pragma once
/// \file RunFileMerge.hpp
/// \brief Merging the run files of separate orbit ranges of one run into the run file of the whole run
/// (issue 15): scheduler array jobs (`run --orbits BEGIN:END`), MPI ranks and their checkpoints share it.
///
/// Each orbit depends only on (seed, orbit index) (run/TrappingRun.hpp), so ranges that cover [0, M) exactly,
/// at the same blocks done, merge into the state a single process computes: the same histograms, subsets,
/// longest segments and orbit states.  The cost is proportional to bins + segments + orbits, never to steps.

#include <filesystem>
#include <string>
#include <vector>

#include "core/run/TrappingRun.hpp"

namespace archipelago {

/// One part of a run and where it came from (a file name, "rank 3"): the name every error is about.
struct RunPart {
  std::string name;
  TrappingState state;
};

/// Merges parts (in any order) whose orbit ranges cover [0, M) of one run exactly.  Throws
/// std::invalid_argument with one line naming the part and the field when they do not fit: a parameter that
/// differs from the first part's ("b.json: field 'seed' is 8 but a.json has 7"), a different 'blocksDone',
/// ranges that overlap or leave orbits out ('orbitBegin'/'orbitEnd'), or no parts.
[[nodiscard]] TrappingState mergeRunParts(std::vector<RunPart> parts);

/// Orbits [begin, end) of a whole (or merged) state, to continue on their own: with the run's statistics so far
/// (subset histograms, longest segments, elapsed time) when `withStatistics`, else with empty ones.  Exactly one
/// slice of a partition takes the statistics; the merge of the continued slices (mergeRunParts) is then the
/// continued whole run, since histograms add and the longest segments of a union are the longest of the
/// parts' longest.  How a distributed run resumes on another number of ranks.
[[nodiscard]] TrappingState sliceRun(const TrappingState& whole, std::uint64_t begin, std::uint64_t end,
                                     bool withStatistics);

inline constexpr const char* kRunManifestFormatName = "archipelago-run-parts";
/// The largest manifest read (a manifest lists one line per part: 16 MiB is about 10⁵ parts).
inline constexpr std::uintmax_t kMaxManifestBytes = std::uintmax_t{1} << 24;
inline constexpr int kRunManifestFormatVersion = 1;

/// A checkpoint of a run kept as parts (one run file per MPI rank): which files, at which blocks done.  The
/// manifest is written atomically after every part is; the parts of a checkpoint have names of their own
/// (blocks done in the name), so a crash leaves the previous manifest and its parts whole.
struct RunManifest {
  std::uint64_t blocksDone = 0;
  struct Part {
    std::string file;  ///< relative to the manifest's folder
    std::uint64_t orbitBegin = 0;
    std::uint64_t orbitEnd = 0;
  };
  std::vector<Part> parts;
};

[[nodiscard]] std::string runManifestText(const RunManifest& manifest);
/// Throws io::BadFile "<name>: …" naming the field of a corrupt or truncated manifest.
[[nodiscard]] RunManifest parseRunManifest(const std::string& text, const std::string& name);
/// True when `text` claims to be a manifest (its "format" field), so a reader can tell it from a run file.
[[nodiscard]] bool looksLikeRunManifest(const std::string& text);
/// Loads a manifest's parts, each checked against the manifest (orbit range, blocks done: the file and the field
/// named), and merges them (mergeRunParts).  Throws std::runtime_error naming the file.
[[nodiscard]] TrappingState loadRunManifest(const std::filesystem::path& manifest);

}  // namespace archipelago
