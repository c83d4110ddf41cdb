#include "core/atlas/AtlasJob.hpp"

#include <stdexcept>
#include <utility>

#include "core/atlas/AtlasExport.hpp"
#include "core/io/AtomicFile.hpp"

namespace archipelago {

Atlas atlasToResume(const AtlasRequest& request, const std::string& text, const std::string& name) {
  Atlas previous;
  try {
    previous = atlasFromJson(text);
  } catch (const std::exception& e) {
    throw std::invalid_argument(name + ": " + e.what());
  }
  if (auto e = resumeError(request, previous)) throw std::invalid_argument(name + ": " + *e);
  return previous;
}

AtlasFileOutcome atlasOrResumeFile(const std::filesystem::path& file, const AtlasRequest& request,
                                   const AtlasProgress& progress, std::stop_token stop) {
  AtlasFileOutcome out;
  std::optional<Atlas> previous;
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) {
    try {
      previous = atlasToResume(request, io::readRegularFile(file, kMaxAtlasFileBytes), file.string());
    } catch (const std::exception& e) {
      out.discarded = e.what();
    }
  }
  if (previous && !previous->cancelled) {
    out.reused = true;
    out.atlas = std::move(*previous);
    return out;
  }
  out.resumed = previous.has_value();
  out.atlas = computeAtlas(request, progress, std::move(stop), previous ? &*previous : nullptr);
  writeAtlasJson(file, out.atlas);
  return out;
}

}  // namespace archipelago
