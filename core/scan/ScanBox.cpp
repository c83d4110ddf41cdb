#include "core/scan/ScanBox.hpp"

#include <charconv>
#include <optional>
#include <cmath>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

MapParameters scanBox(double K) {
  if (auto e = realRangeError("K", K, 0, kScanMaxK,
                              io::formatC("for a scan: its box is -2 sqrt(K) - %g to sqrt(K) + %g", kScanBoxMargin,
                                          kScanBoxMargin)))
    throw std::invalid_argument(*e);
  const double r = std::sqrt(K);
  MapParameters box;
  box.K = K;
  box.xmin = -2 * r - kScanBoxMargin;
  box.xmax = r + kScanBoxMargin;
  return box;
}

std::vector<double> scanValues(double from, double to, double step) {
  if (!(step > 0) || !std::isfinite(step)) throw std::invalid_argument("the step of a K range must be positive");
  if (!(to >= from) || !std::isfinite(from) || !std::isfinite(to))
    throw std::invalid_argument("a K range must run upwards (from <= to)");
  const double intervals = (to - from) / step;
  if (intervals > 1e4) throw std::invalid_argument("a K range may hold at most 10^4 values");
  const auto n = static_cast<std::size_t>(std::floor(intervals + 1e-9)) + 1;
  std::vector<double> values;
  values.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string text = io::formatC("%.12g", from + static_cast<double>(i) * step);
    values.push_back(*io::parseDoubleC(text));  // the C locale: "%.12g" never writes a decimal comma here
  }
  return values;
}

void checkScanValues(const std::vector<double>& K) {
  if (K.empty()) throw std::invalid_argument("the K list is empty: give at least one K");
  for (std::size_t i = 0; i < K.size(); ++i) {
    (void)scanBox(K[i]);  // the range of the box rule
    for (std::size_t j = 0; j < i; ++j)
      if (K[j] == K[i]) throw std::invalid_argument("the K list holds K = " + scanKText(K[i]) + " twice");
  }
}

std::vector<double> parseScanValues(std::string_view text) {
  const auto trim = [](std::string_view t) {
    while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.remove_prefix(1);
    while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.remove_suffix(1);
    return t;
  };
  // Each word by the one number reader (finite, the whole word, never the locale).
  const auto split = [&](std::string_view t, char sep) {
    std::vector<double> values;
    while (true) {
      const std::size_t end = t.find(sep);
      const std::string_view word = trim(t.substr(0, end));
      const std::optional<double> v = io::toNumber<double>(word);
      if (!v) throw std::invalid_argument("'" + io::shortText(word) + "' in the K list is not a finite number");
      values.push_back(*v);
      if (end == std::string_view::npos) return values;
      t.remove_prefix(end + 1);
    }
  };
  text = trim(text);
  if (text.empty()) throw std::invalid_argument("the K list is empty: give at least one K");
  std::vector<double> values;
  if (text.find(':') != std::string_view::npos) {
    const std::vector<double> r = split(text, ':');
    if (r.size() != 3) throw std::invalid_argument("a K range is FROM:TO:STEP, e.g. 0.05:1.3:0.05");
    values = scanValues(r[0], r[1], r[2]);
  } else {
    values = split(text, ',');
  }
  checkScanValues(values);
  return values;
}

std::string scanKText(double K) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, K);
  return std::string(text, result.ptr);
}

}  // namespace archipelago
