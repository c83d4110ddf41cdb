#pragma once
/// \file ScanBox.hpp
/// \brief The K scan of §5 ("We have measured f_t for K between 0 and 1.3 at intervals of 0.05"): the list of K,
/// its one reader (the CLI's --K, the GUI's K field, the report), and the box of each K.
///
/// The box rule.  The paper does not give its boxes for the scan; appendix B only requires xmin < −√K, and
/// appendix A shows that a larger box adds short segments without changing b₂ f_t for large t (eq. A3).  The
/// box must hold the island: for small K the island of eq. (hamb) runs from the separatrix's far crossing
/// X = −2 to the hyperbolic point X = 1 in units of √K, i.e. −2√K ≤ x ≤ √K.  We take that extent with a margin
/// of 0.2 on each side:
///     xmin = −2√K − 0.2,   xmax = √K + 0.2.
/// At K = 0.1 this is (−0.832, 0.516), close to the paper's (−0.8, 0.5); at K = 0 (no island) a box of side 0.4
/// around the tangent point; at K = 1.3 (past the period doublings at K = 1, 1.25, whose orbits lie at
/// x = −1 ∓ √(K − 1), §2) (−2.48, 1.34), which still holds them.

#include <string>
#include <string_view>
#include <vector>

#include "core/map/MapParameters.hpp"

namespace archipelago {

inline constexpr double kScanBoxMargin = 0.2;
/// The scan's K must lie in [0, kScanMaxK]: the box rule needs √K, and beyond 4 the box's side exceeds 6.
inline constexpr double kScanMaxK = 4;

/// The box of K (the rule above).  Throws std::invalid_argument naming K when K is not in [0, kScanMaxK].
[[nodiscard]] MapParameters scanBox(double K);

/// K = from, from + step, …, up to `to` (included when it is within 10⁻⁹ step of a grid point), each rounded to
/// 12 significant digits so that 0.05·3 is 0.15, not 0.15000000000000002.  Throws std::invalid_argument when
/// step ≤ 0, to < from, or the list would have more than 10⁴ values.
[[nodiscard]] std::vector<double> scanValues(double from, double to, double step);

/// Every K checked: each in the box rule's range [0, kScanMaxK] (scanBox), none twice, at least one.  Throws
/// std::invalid_argument naming the offending K.
void checkScanValues(const std::vector<double>& K);

/// The K list of a text: "FROM:TO:STEP" (scanValues) or "K1, K2, …" (commas, blanks allowed around them), each K
/// read by the one number reader (core/io/NumberText.hpp); then checkScanValues.  Throws std::invalid_argument
/// saying what is wrong (an empty list, a word that is not a number, NaN, a K outside the range, a K twice).  The
/// one reader of K lists: the CLI's --K, the GUI's K-scan dialog and the report.
[[nodiscard]] std::vector<double> parseScanValues(std::string_view text);

/// The paper's list (§5: "K between 0 and 1.3 at intervals of 0.05"), as a text parseScanValues reads.
inline constexpr const char* kPaperScanValuesText = "0.05:1.3:0.05";

/// The shortest text that reads back as K ("0.05"): the run file's name and the messages.
[[nodiscard]] std::string scanKText(double K);


}  // namespace archipelago
