#include "core/tail/TailJob.hpp"

#include <cmath>
#include <utility>

#include "core/io/NumberText.hpp"
#include "core/tail/TailFile.hpp"

namespace archipelago {

TailState runTailJob(TailState state, const TailJobOptions& options, LastCheckpoint& last,
                     const TailObserver& progress, std::stop_token stop) {
  if (state.finished()) return state;
  CheckpointClock clock(options.checkpointSeconds);
  const auto observer = [&](const TailState& s, const TailProgress& p) {
    if (!options.checkpoint.empty() && !s.finished() && clock.due())
      writeCheckpoint([&] { saveTailFile(options.checkpoint, s); }, options.checkpoint.string(), 0, last,
                      options.checkpointSeconds, options.warning);
    if (progress) progress(s, p);
  };
  return runTail(std::move(state), options.run, observer, std::move(stop));
}

void saveTailOrSayWhere(const std::filesystem::path& path, const TailState& state, const LastCheckpoint& last,
                        const std::string& howToResume) {
  saveOrRescue(
      path, [&](const std::filesystem::path& p) { saveTailFile(p, state); }, "tail run",
      state.finished() ? " (finished)" : " (unfinished)",
      last.path.empty() ? std::string() : "the last checkpoint is in " + last.path + howToResume);
}

std::string tailComparisonCsv(const TailComparison& c) {
  std::string out = "# brute-force steps: " + io::formatC("%.17g", c.bruteSteps) + "\n# alpha: " +
                    io::formatC("%.17g", c.alpha) + "\n";
  out += "t,P,P_error,reliable,brute_P,brute_error,brute_segments,z,tail_steps,brute_steps_same_error,measured\n";
  const auto n = [](double v) { return std::isfinite(v) ? io::formatC("%.17g", v) : std::string(); };
  for (const TailComparisonLevel& l : c.levels)
    out += n(l.t) + "," + n(l.P) + "," + n(l.PError) + "," + (l.reliable ? "1" : "0") + "," + n(l.bruteP) + "," +
           n(l.bruteError) + "," + std::to_string(l.bruteSegments) + "," + n(l.z) + "," + n(l.tailSteps) + "," +
           n(l.bruteStepsSameError) + "," + (l.bruteStepsMeasured ? "1" : "0") + "\n";
  return out;
}

}  // namespace archipelago
