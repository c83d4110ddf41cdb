#include "core/report/ReportItem.hpp"

#include <cmath>

namespace archipelago::report {

const char* markText(Mark m) noexcept {
  switch (m) {
    case Mark::agrees: return "agrees";
    case Mark::differsExplained: return "differs, explained";
    case Mark::differs: return "DIFFERS";
    case Mark::notAtThisSize: return "not reproducible at this size";
    case Mark::reported: return "reported (open question)";
    case Mark::notComputed: return "not computed";
  }
  return "?";
}

bool passes(const paper::Statement& s, std::optional<double> ours, double error, std::optional<double> target) noexcept {
  if (!ours || !target || !std::isfinite(*ours) || !std::isfinite(*target)) return false;
  const double slack = s.tolerance + 3 * (std::isfinite(error) ? error : 0);
  switch (s.comparison) {
    case paper::Comparison::value:
    case paper::Comparison::range: return std::abs(*ours - *target) <= slack;
    case paper::Comparison::atLeast: return *ours >= *target - slack;
    case paper::Comparison::atMost: return *ours <= *target + slack;
    case paper::Comparison::openQuestion: return false;
  }
  return false;
}

ReportItem makeItem(std::string_view id, std::optional<double> ours, double error, bool fullSize, std::string command,
                    std::string note, std::optional<double> reference) {
  ReportItem it;
  it.statement = &paper::statement(id);
  it.ours = ours && std::isfinite(*ours) ? ours : std::nullopt;
  it.error = std::isfinite(error) ? error : 0;
  it.reference = reference;
  it.command = std::move(command);
  it.note = std::move(note);
  if (it.statement->comparison == paper::Comparison::openQuestion) it.mark = Mark::reported;
  else if (it.statement->needsFullSize && !fullSize) it.mark = Mark::notAtThisSize;
  else if (!it.ours) it.mark = Mark::notComputed;
  else it.mark = passes(*it.statement, it.ours, it.error, it.target()) ? Mark::agrees : Mark::differs;
  return it;
}

ReportItem makeItemWithin(std::string_view id, std::optional<double> ours, double error, double tolerance,
                          bool fullSize, std::string command, std::string note) {
  ReportItem it = makeItem(id, ours, error, fullSize, std::move(command), std::move(note));
  if (std::isfinite(tolerance) && tolerance >= 0) it.tolerance = tolerance;
  if (it.mark != Mark::agrees && it.mark != Mark::differs) return it;
  if (!it.tolerance) {
    it.mark = Mark::notComputed;
    return it;
  }
  paper::Statement within = *it.statement;
  within.tolerance = *it.tolerance;
  it.mark = passes(within, it.ours, 0, it.target()) ? Mark::agrees : Mark::differs;
  return it;
}

void explainDifference(ReportItem& item, const std::string& reason) {
  if (item.mark != Mark::differs) return;
  item.mark = Mark::differsExplained;
  item.note += (item.note.empty() ? "" : "; ") + reason;
}

}  // namespace archipelago::report
