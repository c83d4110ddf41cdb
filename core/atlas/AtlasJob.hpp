#pragma once
/// \file AtlasJob.hpp
/// \brief The atlas as a job (issue 51: its reuse-or-resume was written three times, in the CLI, the report and
/// Python): the atlas to continue, read and checked against the request in one call, and the report's "reuse a
/// finished file, resume a stopped one, else compute" with the file written at the end.

#include <filesystem>
#include <optional>
#include <stop_token>
#include <string>

#include "core/atlas/Atlas.hpp"

namespace archipelago {

/// The atlas stopped early to continue, from the JSON text of an atlas file (atlasFromJson) and checked against
/// `request` (resumeError).  Throws std::invalid_argument "<name>: <reason>" (name: how the front end names the
/// atlas given, e.g. "--resume r.json", "resume").
[[nodiscard]] Atlas atlasToResume(const AtlasRequest& request, const std::string& text, const std::string& name);

/// What atlasOrResumeFile() found and did.
struct AtlasFileOutcome {
  Atlas atlas;              ///< finished, or stopped (cancelled) and saved
  bool reused = false;      ///< the file held the finished atlas of this request: nothing was computed
  bool resumed = false;     ///< the file held a stopped atlas of this request: continued
  std::string discarded;    ///< why a file that held something else was not used (then computed anew), or empty
};

/// The report's atlas step: `file` reused when it holds the finished atlas of `request`, continued when it holds one
/// stopped early, computed anew otherwise (a file of another request or unreadable: `discarded` says why); the
/// atlas is written to `file` (writeAtlasJson, atomically) whenever it was computed, finished or stopped.
[[nodiscard]] AtlasFileOutcome atlasOrResumeFile(const std::filesystem::path& file, const AtlasRequest& request,
                                                 const AtlasProgress& progress = {}, std::stop_token stop = {});

}  // namespace archipelago
