#pragma once
/// \file CliCommon.hpp
/// \brief What archipelago-cli's subcommands share: the one number parser, the options that use it, and the
/// map options.
///
/// Numbers on the command line are read strictly, by one parser (issue #12, item 2: no silent wrap):
///   - the whole text must be the number (no leading blanks, nothing after it);
///   - an integer option takes plain decimal digits (an optional sign) and must fit its type: `--seed=-5` or
///     `--seed=18446744073709551616` is an error naming the option, the text and the range, never a wrapped
///     value;
///   - a real option takes what strtod/strtold reads (e.g. 0.1, -8e-1, 0x1p-3) and must be finite: nan and inf
///     are errors, and so is a value that overflows.
/// Every error is a std::invalid_argument whose text is the one line main() prints after "ERROR: ", e.g.
/// "--steps = -1 must be an integer in [0, 18446744073709551615]".
/// Ranges narrower than the type's (q ≥ 1, the box's xmin < −√K, …) are core's validation, not the parser's.

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/map/FixedPointMap.hpp"  // PhysicalPoint
#include "core/map/MapParameters.hpp"
#include "core/portrait/Viewport.hpp"    // PhysicalRect

namespace archipelago::cli {

/// `text` read strictly as a T (the rules above), or nothing.
template <class T>
[[nodiscard]] std::optional<T> toNumber(std::string_view text) {
  static_assert(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>);
  const bool plus = !text.empty() && text.front() == '+';  // from_chars and strtod differ on '+'
  if (plus) text.remove_prefix(1);
  if (text.empty() || text.front() == '+' || (plus && text.front() == '-') ||
      std::isspace(static_cast<unsigned char>(text.front())))
    return {};
  if constexpr (std::is_integral_v<T>) {
    T value{};
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value, 10);
    if (error != std::errc{} || end != text.data() + text.size()) return {};
    return value;
  } else {
    const std::string copy(text);  // strtod needs a terminated string
    char* end = nullptr;
    T value{};
    if constexpr (std::is_same_v<T, float>) value = std::strtof(copy.c_str(), &end);
    else if constexpr (std::is_same_v<T, double>) value = std::strtod(copy.c_str(), &end);
    else value = std::strtold(copy.c_str(), &end);
    if (end != copy.c_str() + copy.size() || !std::isfinite(value)) return {};
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

/// The value of option `option` given as `text`; throws std::invalid_argument
/// "<option> = <text> must be <numberRule<T>()>" when toNumber<T> rejects it.
template <class T>
[[nodiscard]] T parseNumber(const std::string& option, const std::string& text) {
  if (const std::optional<T> value = toNumber<T>(text)) return *value;
  throw std::invalid_argument(option + " = " + text + " must be " + numberRule<T>());
}

/// Exactly `count` numbers separated by `separator` (e.g. "x,y", "WxH"), each read by toNumber<T>; throws
/// std::invalid_argument "<option> '<text>' must be <what>" otherwise.
template <class T>
[[nodiscard]] std::vector<T> parseNumbers(const std::string& option, const std::string& text, char separator,
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
  throw std::invalid_argument(option + " '" + text + "' must be " + what);
}

/// The shortest text that reads back as `value` (for --help's defaults).
template <class T>
[[nodiscard]] std::string formatNumber(T value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

/// Adds a numeric option `name` (CLI11 names: "--a" or "--a,--b") that stores into `value` through parseNumber<T> (so every number of the CLI
/// is read by the one parser); --help shows `value`'s current value as the default.
template <class T>
CLI::Option* addNumberOption(CLI::App& command, const std::string& name, T& value, const std::string& help) {
  const std::string shown = name.substr(0, name.find(','));  // "--longestKept,--longest": errors name the first
  CLI::Option* option = command.add_option_function<std::string>(
      name, [&value, shown](const std::string& text) { value = parseNumber<T>(shown, text); }, help);
  option->type_name(std::is_integral_v<T> ? "INT" : "FLOAT");
  option->default_str(formatNumber(value));
  return option;
}

/// The most seeds one `run --seeds` makes (each is a whole run).
inline constexpr std::size_t kMaxSeeds = 1000;

/// The seeds of `--seeds TEXT`: comma-separated items, each a seed "K" or a range "A..B" (A ≤ B), every
/// number read by toNumber<std::uint64_t> and within the seed parameter's range (parameterRules()).  Throws
/// std::invalid_argument with one line naming `option` for anything else: an empty item, a sign, a fraction,
/// nan or inf, a number too large, a reversed range, more than kMaxSeeds seeds, a seed given twice.
/// The orbit range of `--orbits BEGIN:END` for a run of M orbits: [BEGIN, END) with BEGIN < END ≤ M; all M
/// orbits when `text` is empty.  Throws std::invalid_argument naming --orbits otherwise.
[[nodiscard]] std::pair<std::uint64_t, std::uint64_t> orbitRange(const std::string& text, std::uint64_t M);

[[nodiscard]] std::vector<std::uint64_t> parseSeedList(const std::string& option, const std::string& text);

/// The run file of one seed of an ensemble: "run.json" → "run.seed-3.json", "out/x" → "out/x.seed-3".
[[nodiscard]] std::string seededPath(const std::string& path, std::uint64_t seed);

/// "x0,x1,y0,y1" (physical coordinates, --view of portrait and indicator) → the rectangle; throws
/// std::invalid_argument "--view '<text>' must be four finite numbers x0,x1,y0,y1 (physical coordinates)".
[[nodiscard]] PhysicalRect parseView(const std::string& text);

/// "WxH" with whole numbers 1 … limit (--size, --seeds); throws std::invalid_argument naming `option` otherwise.
[[nodiscard]] std::pair<int, int> parseSize(const std::string& text, const std::string& option, int limit);

/// "x,y" → the physical point; throws std::invalid_argument "<option> '<text>' must be two finite numbers x,y".
[[nodiscard]] PhysicalPoint parsePoint(const std::string& option, const std::string& text);

/// Adds --K, --xmin and --xmax (defaults: the paper's K = 0.1 box, §5) to a subcommand.
void addMapOptions(CLI::App& command, MapParameters& params);

/// Adds --kernel NAME (the instruction-set path; empty: $ARCHIPELAGO_KERNEL, else the fastest the CPU supports).
/// The command passes the name to selectKernel() (kernels/KernelDispatch.hpp), which validates it.
void addKernelOption(CLI::App& command, std::string& name);

}  // namespace archipelago::cli
