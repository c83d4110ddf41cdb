#pragma once
/// \file CliCommon.hpp
/// \brief What archipelago-cli's subcommands share: the one number parser, the options that use it, and the
/// map options.
///
/// Numbers on the command line are read strictly, by core's one reader (core/io/NumberText.hpp: no silent
/// wrap, no locale, exact whole numbers for integer options); every error is a std::invalid_argument whose text
/// is the one line main() prints after "ERROR: ", e.g. "--steps = -1 must be an integer in [0, 18446744073709551615]".
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

#include "core/io/NumberText.hpp"
#include "core/map/FixedPointMap.hpp"  // PhysicalPoint
#include "core/map/MapParameters.hpp"
#include "core/view/Viewport.hpp"    // PhysicalRect

namespace archipelago::cli {

/// The command line's name of a setting core names by its role (core/tail/TailPlan.hpp): "--" and the role
/// ("checkpoint-interval" → "--checkpoint-interval"): the options are spelled as core's roles.
[[nodiscard]] std::string flagOf(std::string_view role);

using io::numberRule;
using io::parseNumber;
using io::parseNumbers;
using io::toNumber;

/// The shortest text that reads back as `value` (for --help's defaults).
template <class T>
[[nodiscard]] std::string formatNumber(T value) {
  return io::shortestText(value);
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

/// The orbit range of `--orbits BEGIN:END` for a run of M orbits: [BEGIN, END) with BEGIN < END ≤ M; all M
/// orbits when `text` is empty.  Throws std::invalid_argument naming --orbits otherwise.
[[nodiscard]] std::pair<std::uint64_t, std::uint64_t> orbitRange(const std::string& text, std::uint64_t M);


/// The run file of one seed of an ensemble: "run.json" → "run.seed-3.json", "out/x" → "out/x.seed-3".
[[nodiscard]] std::string seededPath(const std::string& path, std::uint64_t seed);

/// "x0,x1,y0,y1" (physical coordinates, --view of portrait and indicator) → the rectangle; throws
/// std::invalid_argument "--view '<text>' must be four finite numbers x0,x1,y0,y1 (physical coordinates)".
[[nodiscard]] PhysicalRect parseView(const std::string& text);

using io::parseSize;  // "WxH" (--size, --seeds): core's reader

/// "x,y" → the physical point; throws std::invalid_argument "<option> '<text>' must be two finite numbers x,y".
[[nodiscard]] PhysicalPoint parsePoint(const std::string& option, const std::string& text);

/// Adds --K, --xmin and --xmax (defaults: the paper's K = 0.1 box, §5) to a subcommand.
void addMapOptions(CLI::App& command, MapParameters& params);

/// Adds --kernel NAME (the instruction-set path; empty: $ARCHIPELAGO_KERNEL, else the fastest the CPU supports).
/// The command passes the name to selectKernel() (kernels/KernelDispatch.hpp), which validates it.
void addKernelOption(CLI::App& command, std::string& name);

/// What a tool does with CLI11's parse exception: --help and --version print as CLI11 prints them (status 0); an
/// error is one line "ERROR: <what>" on stderr (not CLI11's message and banner over several lines), status 2 or
/// CLI11's.  archipelago-cli and archipelago-mpi (issue 36) both end their parse with it.
int parseErrorStatus(const CLI::App& app, const CLI::ParseError& e);

}  // namespace archipelago::cli
