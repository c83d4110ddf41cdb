#pragma once
/// \file ReportItem.hpp
/// \brief A statement of the paper (core/paper/PaperTable.hpp) with our value and its mark.  The words, the paper's
/// value, the tolerance and why are the table's; this holds only what a report computes: our value, its error, what
/// it is compared with when that is not the paper's number, the command that reproduces it and a note.
///
/// Marks (issue #26: every item can fail; none compares theory with theory):
///   agrees            the comparison of the statement holds (Comparison::value: |ours − target| ≤ tolerance + 3σ;
///                     atLeast: ours ≥ target − tolerance − 3σ; atMost: ours ≤ target + tolerance + 3σ);
///   differs           it does not, and no reason is known: a failure of the report;
///   differsExplained  it does not, for a reason stated in the note;
///   notAtThisSize     a statement that needs a run of the paper's size (needsFullSize) on a quick report;
///   reported          the paper's open question (Comparison::openQuestion): a value, never a verdict;
///   notComputed       no value (the computation could not be done; the note says why).
/// The target is the paper's value, or `reference` when the statement compares with a prediction of ours (the
/// longest segment in the run's finite box, not the paper's infinite-box t_max).  The tolerance is the table's, or
/// `tolerance` when the report computes it from its data (makeItemWithin: tail-gamma-K's, from the errors and the
/// spread over K).

#include <optional>
#include <string>
#include <string_view>

#include "core/paper/PaperTable.hpp"

namespace archipelago::report {

enum class Mark { agrees, differsExplained, differs, notAtThisSize, reported, notComputed };

[[nodiscard]] const char* markText(Mark m) noexcept;

struct ReportItem {
  const paper::Statement* statement = nullptr;
  std::optional<double> ours;
  double error = 0;                      ///< one sigma of ours (0: exact to rounding, or unknown)
  std::optional<double> reference;       ///< compared instead of the paper's value (see the file comment)
  std::optional<double> tolerance;       ///< replaces the table's (makeItemWithin), every error included
  Mark mark = Mark::notComputed;
  std::string command;                   ///< one command that reproduces it alone
  std::string note;                      ///< how this value came about, or why it differs

  [[nodiscard]] std::string_view id() const noexcept { return statement->id; }
  /// The value ours is compared with: `reference`, else the paper's.
  [[nodiscard]] std::optional<double> target() const noexcept { return reference ? reference : statement->paper; }
  /// The tolerance ours was checked against: `tolerance`, else the table's.
  [[nodiscard]] double toleranceUsed() const noexcept { return tolerance.value_or(statement->tolerance); }
};

/// Whether `ours ± error` passes the statement's comparison against `target` (false without a value).
[[nodiscard]] bool passes(const paper::Statement& s, std::optional<double> ours, double error,
                          std::optional<double> target) noexcept;

/// The item of statement `id` (paper::statement(id): throws std::out_of_range for an unknown id) with its mark:
/// reported for an open question, notComputed without a finite value, notAtThisSize for a statement that needs the
/// paper's size when `fullSize` is false, else agrees or differs by passes().
[[nodiscard]] ReportItem makeItem(std::string_view id, std::optional<double> ours, double error, bool fullSize,
                                  std::string command, std::string note,
                                  std::optional<double> reference = std::nullopt);

/// An item whose tolerance the report computes from its data (the table's tolerance is 0 and its words give the
/// rule): makeItem()'s marks, but the comparison's slack is `tolerance` alone, which holds every error (no 3σ is
/// added); kept in the item for its files.  A tolerance that is not a finite number ≥ 0 gives notComputed where a
/// mark was due.
[[nodiscard]] ReportItem makeItemWithin(std::string_view id, std::optional<double> ours, double error, double tolerance,
                                        bool fullSize, std::string command, std::string note);

/// A differing item with a known reason: differsExplained, the reason added to the note.  Any other mark is kept.
void explainDifference(ReportItem& item, const std::string& reason);

}  // namespace archipelago::report
