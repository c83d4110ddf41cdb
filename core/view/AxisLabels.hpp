#pragma once
/// \file AxisLabels.hpp
/// \brief How the portrait's axes label a view at any depth: plain numbers while a few digits tell the ticks
/// apart, else offset notation — the view's reference point once (in the axis title), the ticks as short offsets
/// from it in units of a power of ten (issue 37, findings 2 and 18: at a view 3·10⁻⁷ wide about x = −0.15 the
/// plain labels "−0.1500000015000000…" ran together).

#include <string>
#include <vector>

namespace archipelago {

struct AxisLabels {
  bool offset = false;   ///< ticks written as (value − reference) / 10^exponent
  int digits = 6;        ///< plain labels: significant digits that tell neighbouring ticks apart
  double reference = 0;  ///< offset: the view's centre rounded to a multiple of 10^exponent
  int exponent = 0;      ///< offset: 10^exponent ≤ the view's width < 10^(exponent+1)
};

/// The labels of an axis showing [lo, hi] (lo < hi, finite): plain with up to 7 significant digits, offset beyond
/// (a view narrower than about 10⁻⁴ of its largest |coordinate|).  A degenerate or non-finite range gives plain, 6 digits.
[[nodiscard]] AxisLabels axisLabelsFor(double lo, double hi);
/// Significant digits that tell apart points a tenth of [lo, hi] apart, at any depth (3 … 19; 6 for a degenerate
/// range): the cursor's coordinates, and the plain labels.
[[nodiscard]] int axisDigits(double lo, double hi);
/// The label of the tick at `value`: plain ("−0.15", "0.0734") or the offset ("−2.5", "0", "5").
[[nodiscard]] std::string axisTickLabel(const AxisLabels& labels, double value);
/// The ticks of an axis showing [lo, hi]: major ticks a round step apart (1, 2 or 5 × 10^k, the smallest giving at
/// most maxMajor steps), at whole multiples of the step from `labels`' reference (0 for plain labels), so that the
/// labels are round and evenly spaced at any depth (issue 53, finding 7: at a view 3·10⁻¹³ wide Qwt's own ticks began
/// at the view's edge, "−1.268, −0.7676, …", the last interval 0.456); minor ticks the same way, at most maxMinor
/// steps per major step.  Empty for a degenerate or non-finite range.
struct AxisTicks {
  std::vector<double> major;
  std::vector<double> minor;
};
[[nodiscard]] AxisTicks axisTicks(const AxisLabels& labels, double lo, double hi, int maxMajor = 8, int maxMinor = 5);
/// What the axis title adds in offset notation: " − (−0.1500000) [×10⁻⁷]" (UTF-8), empty for plain labels.
[[nodiscard]] std::string axisTitleSuffix(const AxisLabels& labels);

}  // namespace archipelago
