#include "core/stats/RunSummary.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/run/TrappingRun.hpp"
#include "core/stats/RunEnsemble.hpp"

namespace archipelago {

namespace {
/// The sources' names, once: the words every front end labels the error with, and the key of Python and JSON.
struct SourceNames {
  DErrorSource source;
  std::string_view words, key;
};
constexpr SourceNames kSourceNames[] = {{DErrorSource::none, "none", "none"},
                                        {DErrorSource::bootstrap, "bootstrap over segments", "bootstrap"},
                                        {DErrorSource::subsets, "subsets of orbits", "subsets"}};
const SourceNames& namesOf(DErrorSource source) noexcept {
  for (const SourceNames& n : kSourceNames)
    if (n.source == source) return n;
  return kSourceNames[0];
}
}  // namespace

std::string_view toString(DErrorSource source) noexcept { return namesOf(source).words; }

std::string_view keyOf(DErrorSource source) noexcept { return namesOf(source).key; }

namespace {
std::string g4(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}
}  // namespace

std::string gammaPText(const TailWindow& w) {
  return g4(w.gammaP) + " [" + g4(w.gammaPInterval.lo) + ", " + g4(w.gammaPInterval.hi) + "] over " + g4(w.from) +
         " <= t <= " + g4(w.to);
}

std::string tailVerdictText(const TailAnalysis& tail) {
  const std::string message = dominanceMessage(tail);
  return message.empty() ? "the tail does not dominate D: its bootstrap error stands" : message;
}

std::string RunSummary::DText() const {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", D);
  std::string text = buffer;
  if (std::isfinite(DError)) {
    std::snprintf(buffer, sizeof buffer, " +- %.2g", DError);
    text += buffer;
  }
  return text + " (" + DErrorNote + ")";
}

RunSummary summarizeRun(const TrappingStatistics& s, const TailAnalysis* tail, std::string_view whyNotJudged) {
  RunSummary r;
  r.spliced = s.splicedAt > 0;
  r.splicedAt = s.splicedAt;
  r.segments = s.segments;
  r.alpha = s.alpha;
  r.alphaError = s.alphaError;
  r.sumTf = s.sumTf;
  r.D = s.D;
  r.DSubsetsError = s.DError;
  r.runD = tail ? tail->D : (r.spliced ? kTailUndefined : s.D);
  if (!tail) {
    r.DErrorNote = "no error: " + std::string(whyNotJudged);
    return r;
  }
  r.judged = true;
  r.dominated = tail->dominated();
  r.verdict = dominanceMessage(*tail);
  r.gammaP = tail->tailFit.gammaP;
  r.gammaPInterval = tail->tailFit.gammaPInterval;
  r.gammaPText = tail->windows.empty() ? std::string(kNoTailFit) : gammaPText(tail->tailFit);
  r.tailVerdict = tailVerdictText(*tail);
  r.runDError = supportedDError(*tail);
  if (r.dominated) {
    r.DErrorNote = "no error: " + r.verdict;
  } else if (r.spliced) {
    r.DError = s.DError;
    r.errorSource = DErrorSource::subsets;
    r.DErrorNote = "spliced; the error: the subsets of orbits of the spliced statistics";
  } else if (std::isfinite(r.runDError)) {
    r.DError = r.runDError;
    r.errorSource = DErrorSource::bootstrap;
    r.DErrorNote = "the error: the bootstrap over segments";
  } else {
    r.DErrorNote = "no error: the bootstrap could not be done";
  }
  return r;
}

RunSummary summarizeRun(const TrappingState& run, const TrappingStatistics& statistics,
                        std::optional<TailAnalysis>* tailOut) {
  if (tailOut) tailOut->reset();
  if (statistics.segments == 0) return summarizeRun(statistics, nullptr, "no segment yet");
  try {
    TailAnalysis tail = analyseTail(ensembleOf({run}));
    RunSummary r = summarizeRun(statistics, &tail);
    if (tailOut) *tailOut = std::move(tail);
    return r;
  } catch (const std::invalid_argument& e) {
    return summarizeRun(statistics, nullptr, e.what());
  }
}

}  // namespace archipelago
