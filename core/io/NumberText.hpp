#pragma once
/// \file NumberText.hpp
/// \brief Numbers as text, both ways: the one strict reader of every number a person types (the CLI's options,
/// the GUI's fields and dialogs, the report's options, the Python module's arguments given as text), and
/// printf-style formatting that never depends on the process locale.
///
/// Reading (toNumber<T>), the rules of every front end (issues #12, #23, #24):
///   - the whole text is the number: no blanks before or after, nothing after it;
///   - an integer is written in decimal, with an optional sign, fraction and exponent, and must be exactly a
///     whole number: "20000000", "2e7", "2.5e3" and "20.0" are integers (the paper writes sizes as 2·10⁹),
///     "2.5", "1e-3", "0x10" and "2e7.5" are not; it must fit T: "-5" for an unsigned type or
///     "18446744073709551616" for a 64-bit one is refused, never wrapped or rounded (the text is evaluated
///     exactly, in integers, never through a double);
///   - a real is what C's strtod reads in the C locale ("0.1", "-8e-1", "0x1p-3"), and must be finite: nan,
///     inf and overflow are refused.  A decimal comma is never a decimal point, whatever the user's locale.
/// Ranges narrower than the type's (q ≥ 1, the box's xmin < −√K, …) are checked by the parameters' rules
/// (core/trapping/TrappingParameters.hpp), not here.
///
/// Writing: formatC() is printf in the C locale; shortestText() the shortest text that reads back exactly.
/// A program that links Qt runs in the user's locale (QCoreApplication calls setlocale(LC_ALL, "")), where
/// printf writes 0.5 as "0,5": a session saved in one locale once did not open in another, and the report's
/// CSV gained columns (issue #23).  Everything core writes to a file, an id or a message goes through these,
/// std::to_chars / std::from_chars, or nlohmann's codec, which never use the locale.

#include <charconv>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace archipelago::io {

/// printf-style formatting in the C locale (the calling thread switches to it for the call only: uselocale).
[[nodiscard]] std::string formatC(const char* format, ...) __attribute__((format(printf, 1, 2)));
/// The same with a va_list.
[[nodiscard]] std::string vformatC(const char* format, std::va_list arguments);

/// The whole of `text` read by C's strtod in the C locale (decimal, hexadecimal, "inf", "nan"; leading blanks
/// are skipped as strtod does), or nothing when `text` is empty or has anything after the number.
[[nodiscard]] std::optional<double> parseDoubleC(std::string_view text);
/// The same for long double (strtold).
[[nodiscard]] std::optional<long double> parseLongDoubleC(std::string_view text);

/// An integer written in decimal (the rules above: exactly whole), as its sign and magnitude, or nothing (not
/// such a number, or a magnitude of 2^64 or more).
struct WholeNumberText {
  bool negative = false;
  std::uint64_t magnitude = 0;
};
[[nodiscard]] std::optional<WholeNumberText> parseWholeNumber(std::string_view text);

/// `text` read strictly as a T (the rules above), or nothing.
template <class T>
[[nodiscard]] std::optional<T> toNumber(std::string_view text) {
  static_assert(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>);
  if (text.empty() || text.front() == ' ' || text.front() == '\t' || text.front() == '\n' || text.front() == '\r' ||
      text.front() == '\v' || text.front() == '\f')
    return {};
  if constexpr (std::is_integral_v<T>) {
    const std::optional<WholeNumberText> w = parseWholeNumber(text);
    if (!w) return {};
    if (w->negative) {
      if constexpr (std::is_unsigned_v<T>) {
        if (w->magnitude != 0) return {};
        return T{0};
      } else {
        const auto limit = static_cast<std::uint64_t>(std::numeric_limits<T>::max()) + 1;  // |min|
        if (w->magnitude > limit) return {};
        return static_cast<T>(-static_cast<std::int64_t>(w->magnitude - 1) - 1);
      }
    }
    if (w->magnitude > static_cast<std::uint64_t>(std::numeric_limits<T>::max())) return {};
    return static_cast<T>(w->magnitude);
  } else {
    std::optional<long double> v;
    if constexpr (std::is_same_v<T, long double>) v = parseLongDoubleC(text);
    else v = parseDoubleC(text);
    if (!v || !std::isfinite(*v)) return {};
    const T value = static_cast<T>(*v);
    if (!std::isfinite(value)) return {};
    return value;
  }
}

/// What a T must be, for error messages: "an integer in [0, 4294967295]" or "a finite number".
template <class T>
[[nodiscard]] std::string numberRule() {
  if constexpr (std::is_integral_v<T>)
    return "an integer in [" + std::to_string(std::numeric_limits<T>::min()) + ", " +
           std::to_string(std::numeric_limits<T>::max()) + "]";
  else
    return "a finite number";
}

/// `text` cut to at most `maxBytes` bytes at a UTF-8 character boundary, with "…" when cut, and its control
/// characters written as escapes (\n, \r, \t, \xHH): what a person typed, or a key or a name read from a file or
/// the environment, quoted in a one-line error message.
[[nodiscard]] std::string shortText(std::string_view text, std::size_t maxBytes = 40);

/// The value of `name` given as `text`; throws std::invalid_argument "<name> = <text> must be <numberRule<T>()>"
/// when toNumber<T> rejects it.
template <class T>
[[nodiscard]] T parseNumber(const std::string& name, std::string_view text) {
  if (const std::optional<T> value = toNumber<T>(text)) return *value;
  throw std::invalid_argument(name + " = " + shortText(text) + " must be " + numberRule<T>());
}

/// Exactly `count` numbers separated by `separator` (e.g. "x,y", "WxH"), each read by toNumber<T>; throws
/// std::invalid_argument "<name> '<text>' must be <what>" otherwise.
template <class T>
[[nodiscard]] std::vector<T> parseNumbers(const std::string& name, std::string_view text, char separator,
                                          std::size_t count, const std::string& what) {
  std::vector<T> values;
  std::string_view rest = text;
  for (bool more = true; more && values.size() < count;) {
    const std::size_t end = rest.find(separator);
    const std::optional<T> value = toNumber<T>(rest.substr(0, end));
    if (!value) break;
    values.push_back(*value);
    more = end != std::string_view::npos;
    if (more) rest.remove_prefix(end + 1);
    else if (values.size() == count) return values;
  }
  throw std::invalid_argument(name + " '" + shortText(text) + "' must be " + what);
}

/// "WxH" with whole numbers 1 … limit (a raster's --size, a seed grid's --seeds; the limit from core/limits' table);
/// throws std::invalid_argument "<option> '<text>' must be WxH with whole numbers 1 ... <limit>" otherwise.
[[nodiscard]] std::pair<int, int> parseSize(const std::string& text, const std::string& option, int limit);

/// The shortest text that reads back as `value` exactly (std::to_chars: never the locale).
template <class T>
[[nodiscard]] std::string shortestText(T value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

}  // namespace archipelago::io
