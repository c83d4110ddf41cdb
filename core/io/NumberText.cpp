#include "core/io/NumberText.hpp"

#include <locale.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace archipelago::io {

namespace {

/// The C locale, created once (newlocale is thread-safe; the handle lives as long as the program).
locale_t cLocale() {
  static const locale_t c = newlocale(LC_ALL_MASK, "C", static_cast<locale_t>(nullptr));
  return c;
}

/// Switches the calling thread to the C locale while it lives.
class InCLocale {
 public:
  InCLocale() : previous_(uselocale(cLocale())) {}
  ~InCLocale() { uselocale(previous_); }
  InCLocale(const InCLocale&) = delete;
  InCLocale& operator=(const InCLocale&) = delete;

 private:
  locale_t previous_;
};

template <class Real>
std::optional<Real> parseC(std::string_view text) {
  if (text.empty() || text.size() > 4096) return std::nullopt;
  const std::string copy(text);  // strtod needs a terminated string
  if (copy.find('\0') != std::string::npos) return std::nullopt;
  char* end = nullptr;
  Real value;
  if constexpr (std::is_same_v<Real, double>) value = strtod_l(copy.c_str(), &end, cLocale());
  else value = strtold_l(copy.c_str(), &end, cLocale());
  if (end == copy.c_str() || end != copy.c_str() + copy.size()) return std::nullopt;
  return value;
}

bool isDigit(char c) { return c >= '0' && c <= '9'; }

}  // namespace

std::string vformatC(const char* format, std::va_list arguments) {
  const InCLocale c;
  std::va_list copy;
  va_copy(copy, arguments);
  char small[256];
  const int n = std::vsnprintf(small, sizeof small, format, copy);
  va_end(copy);
  if (n < 0) throw std::invalid_argument(std::string("bad format '") + format + "'");
  if (static_cast<std::size_t>(n) < sizeof small) return std::string(small, static_cast<std::size_t>(n));
  std::string large(static_cast<std::size_t>(n) + 1, '\0');
  std::vsnprintf(large.data(), large.size(), format, arguments);
  large.resize(static_cast<std::size_t>(n));
  return large;
}

std::string formatC(const char* format, ...) {
  std::va_list arguments;
  va_start(arguments, format);
  struct End {
    std::va_list& a;
    ~End() { va_end(a); }
  } end{arguments};
  return vformatC(format, arguments);
}

std::optional<double> parseDoubleC(std::string_view text) { return parseC<double>(text); }
std::optional<long double> parseLongDoubleC(std::string_view text) { return parseC<long double>(text); }

std::optional<WholeNumberText> parseWholeNumber(std::string_view text) {
  WholeNumberText result;
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) result.negative = text[i++] == '-';
  std::string digits;  // the mantissa's digits, integer part then fraction
  long long fractionDigits = 0;
  bool any = false;
  for (; i < text.size() && isDigit(text[i]); ++i) digits += text[i], any = true;
  if (i < text.size() && text[i] == '.') {
    for (++i; i < text.size() && isDigit(text[i]); ++i) digits += text[i], ++fractionDigits, any = true;
  }
  if (!any) return std::nullopt;
  long long exponent = 0;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool negativeExponent = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) negativeExponent = text[i++] == '-';
    if (i == text.size() || !isDigit(text[i])) return std::nullopt;
    for (; i < text.size() && isDigit(text[i]); ++i)
      if (exponent < 100000) exponent = exponent * 10 + (text[i] - '0');  // beyond any whole uint64
    if (negativeExponent) exponent = -exponent;
  }
  if (i != text.size()) return std::nullopt;
  // value = digits · 10^(exponent − fractionDigits), evaluated exactly.
  const std::size_t first = digits.find_first_not_of('0');
  if (first == std::string::npos) return result;  // zero (and "-0" is 0)
  digits.erase(0, first);
  long long shift = exponent - fractionDigits;
  while (shift < 0 && !digits.empty() && digits.back() == '0') digits.pop_back(), ++shift;
  if (shift < 0) return std::nullopt;  // a fraction remains
  if (static_cast<long long>(digits.size()) + shift > 20) return std::nullopt;  // ≥ 10^20 > 2^64
  digits.append(static_cast<std::size_t>(shift), '0');
  unsigned __int128 v = 0;
  for (const char c : digits) v = v * 10 + static_cast<unsigned>(c - '0');
  if (v > std::numeric_limits<std::uint64_t>::max()) return std::nullopt;
  result.magnitude = static_cast<std::uint64_t>(v);
  return result;
}

std::string shortText(std::string_view text, std::size_t maxBytes) {
  std::size_t cut = text.size();
  if (cut > maxBytes) {
    cut = maxBytes;  // never inside a UTF-8 sequence
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  }
  std::string out;
  for (const char c : text.substr(0, cut)) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (u < 0x20 || u == 0x7F) out += formatC("\\x%02X", u);  // one line, whatever was typed (issue 36)
    else out += c;
  }
  return cut < text.size() ? out + "…" : out;
}

std::pair<int, int> parseSize(const std::string& text, const std::string& option, int limit) {
  const std::string rule = "WxH with whole numbers 1 ... " + std::to_string(limit);
  const auto v = parseNumbers<int>(option, text, 'x', 2, rule);
  if (v[0] < 1 || v[1] < 1 || v[0] > limit || v[1] > limit)
    throw std::invalid_argument(option + " '" + text + "' must be " + rule);
  return {v[0], v[1]};
}

}  // namespace archipelago::io
