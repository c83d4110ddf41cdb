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
  return formatted(d, 4);
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
