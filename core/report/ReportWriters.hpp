#pragma once
/// \file ReportWriters.hpp
/// \brief The report's files that need no Qt: items.csv and index.html (app/reproduce writes them, and the PDF
/// through ui/report).  Text never depends on the locale (core/io/NumberText.hpp; issue #23).

#include <optional>
#include <string>
#include <vector>

#include "core/report/ReportItem.hpp"

namespace archipelago::report {

/// A figure of the report: "6a" (the paper's numbering, docs/design.md, "Figures") or S1…, T, C (ours), its caption (HTML) and the
/// stem of its files under figures/ (stem.png, stem.svg).
struct ReportFigure {
  std::string number, caption, file;
};

/// What index.html shows besides the items and figures.
struct ReportPage {
  std::string size;        ///< "quick" or "full"
  double seconds = 0;      ///< the report's wall time
  std::vector<ReportItem> items;
  std::vector<ReportFigure> figures;
};

/// "1.23457 ± 0.012", "—" without a value.
[[nodiscard]] std::string numberText(const std::optional<double>& v, double error = 0);

/// items.csv: a header row, then one row per item: id, section, statement, paper_value (as printed), paper, ours,
/// error, compared_with (the reference when not the paper's value), tolerance, mark, command, note (12 columns).
[[nodiscard]] std::string itemsCsv(const std::vector<ReportItem>& items);

/// The counts of each mark as one sentence ("26 of 34 statements agree, …").
[[nodiscard]] std::string markSummary(const std::vector<ReportItem>& items, bool full);

/// index.html: the summary, the table of statements, the figures.
[[nodiscard]] std::string indexHtml(const ReportPage& page);

/// HTML-escapes <, > and &.
[[nodiscard]] std::string html(const std::string& text);

}  // namespace archipelago::report
