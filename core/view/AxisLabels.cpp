#include "core/view/AxisLabels.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace archipelago {

namespace {
constexpr int kMaxPlainDigits = 7;  // "-0.1500015": ten characters, as wide as a label should get

std::string formatted(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

/// "⁻⁷", "³": the exponent in superscript digits (UTF-8).
std::string superscript(int n) {
  static const char* const kDigits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string s = n < 0 ? "⁻" : "";
  const std::string digits = std::to_string(n < 0 ? -n : n);
  for (const char c : digits) s += kDigits[c - '0'];
  return s;
}
/// The smallest of 1, 2, 5 × 10^k at least `v` (> 0, finite).
double roundStep(double v) {
  const double power = std::pow(10.0, std::floor(std::log10(v)));
  for (const double n : {1.0, 2.0, 5.0})
    if (n * power >= v * (1 - 1e-9)) return n * power;
  return 10 * power;
}

/// reference + k·step for every k with the tick inside [lo, hi] (a step's billionth of slack at the ends).
std::vector<double> ticksFrom(double reference, double step, double lo, double hi) {
  std::vector<double> ticks;
  const double slack = 1e-9 * step;
  const double first = std::ceil((lo - reference - slack) / step), last = std::floor((hi - reference + slack) / step);
  for (double k = first; k <= last; ++k) ticks.push_back(reference + k * step);
  return ticks;
}
}  // namespace

int axisDigits(double lo, double hi) {
  const double width = hi - lo, magnitude = std::max(std::fabs(lo), std::fabs(hi));
  if (!std::isfinite(width) || !std::isfinite(magnitude) || !(width > 0)) return 6;
  // Those of the magnitude over the width, and 3 more.
  return std::clamp(static_cast<int>(std::ceil(std::log10(std::max(magnitude, width) / width))) + 3, 3, 19);
}

AxisLabels axisLabelsFor(double lo, double hi) {
  AxisLabels labels;
  const double width = hi - lo, magnitude = std::max(std::fabs(lo), std::fabs(hi));
  if (!std::isfinite(width) || !std::isfinite(magnitude) || !(width > 0)) return labels;
  const int digits = axisDigits(lo, hi);
  if (digits <= kMaxPlainDigits) {
    labels.digits = digits;
    return labels;
  }
  labels.offset = true;
  labels.exponent = static_cast<int>(std::floor(std::log10(width)));
  const double unit = std::pow(10.0, labels.exponent);
  labels.reference = std::nearbyint(0.5 * (lo + hi) / unit) * unit;
  return labels;
}

std::string axisTickLabel(const AxisLabels& labels, double value) {
  if (!labels.offset) return formatted(value, labels.digits);
  const double unit = std::pow(10.0, labels.exponent);
  double d = (value - labels.reference) / unit;
  // The reference's own tick: "0", never "-0" or "2.8e-08" (the round-off of the reference and of the tick, a few
  // ulps of their magnitude; ticks are whole tenths of the unit apart).
  const double noise = 64 * std::numeric_limits<double>::epsilon() * std::max(std::fabs(value), std::fabs(labels.reference)) / unit;
  if (std::fabs(d) < std::max(noise, 1e-6)) d = 0;
  // Ticks are whole multiples of at least a tenth of the unit: the round-off of the deepest views (a few ulps of the
  // coordinate, 10⁻³ of the unit at a view 3·10⁻¹³ wide) is not a digit of the label ("0.4995" was 0.5).
  const double rounded = std::nearbyint(d * 100) / 100;
  return formatted(rounded == 0 ? 0.0 : rounded, 4);
}

AxisTicks axisTicks(const AxisLabels& labels, double lo, double hi, int maxMajor, int maxMinor) {
  AxisTicks ticks;
  const double width = hi - lo;
  if (!std::isfinite(width) || !(width > 0) || maxMajor < 1) return ticks;
  const double step = roundStep(width / maxMajor);
  const double reference = labels.offset ? labels.reference : 0.0;
  ticks.major = ticksFrom(reference, step, lo, hi);
  if (maxMinor < 2) return ticks;
  for (const double t : ticksFrom(reference, roundStep(step / maxMinor), lo, hi))
    if (std::none_of(ticks.major.begin(), ticks.major.end(), [&](double m) { return std::fabs(m - t) < 1e-6 * step; }))
      ticks.minor.push_back(t);
  return ticks;
}

std::string axisTitleSuffix(const AxisLabels& labels) {
  if (!labels.offset) return {};
  // The reference to the digits its rounding kept: those above 10^exponent, and one more.
  const double magnitude = std::fabs(labels.reference);
  const int digits = magnitude > 0 ? std::clamp(static_cast<int>(std::floor(std::log10(magnitude))) - labels.exponent + 2, 1, 17)
                                   : 1;
  const std::string reference = formatted(labels.reference, digits);
  return " − (" + (labels.reference < 0 ? "−" + reference.substr(1) : reference) + ") [×10" +
         superscript(labels.exponent) + "]";
}

}  // namespace archipelago
