#pragma once
/// \file InputRules.hpp
/// \brief The one layer through which every front end reads a number a person types (issue #24): the CLI's
/// options, the GUI's parameter panel and dialogs, the report's options, the Python module's arguments.
///
/// A typed value is read by the one strict reader (core/io/NumberText.hpp: "2e7" is the integer 20000000
/// everywhere, a decimal comma is never a point, nothing is wrapped or rounded) and checked against the one table
/// of ranges: the run's parameters (parameterRules(), core/trapping/TrappingParameters.hpp) and the settings that
/// are not parameters (settingRules(): the thread count).  Every front end shows the message this layer makes, so
/// a rule has one wording.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/limits/Limits.hpp"  // limits::kThreads, threadsError
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago {

/// The largest thread count anything accepts: the one table's (core/limits/Limits.hpp).
inline constexpr int kMaxThreads = limits::kThreads;

/// The settings a person types besides the parameters: "threads" (0: one per core).
[[nodiscard]] std::span<const ParameterRule> settingRules() noexcept;

/// The rule of a parameter or a setting, or nullptr.
[[nodiscard]] const ParameterRule* findInputRule(std::string_view key) noexcept;

/// `text` read for input `key`: a whole number, or a finite real.  Throws std::invalid_argument with the one
/// message of every front end: "<key> = <text> must be a whole number in <range>" or "<key> = <text> must be a
/// finite number" (the text quoted at most 40 bytes), or "unknown input '<key>'".  A setting's range is checked
/// here ("threads = 300 must lie in [0, 256] …"); a parameter's range and the rules between parameters (q ≥ 1,
/// xmin < −√K, subsets ≤ M, …) are validationErrors()'s, so each has one message.
[[nodiscard]] ParameterValue readInput(std::string_view key, std::string_view text);

/// The seeds of a seed list `text` (the CLI's --seeds): comma-separated items, each a seed "K" or a range "A..B"
/// (A ≤ B), every number read by io::toNumber<std::uint64_t> and within the seed parameter's range
/// (parameterRules()), at most limits::kSeeds in all.  Throws std::invalid_argument with one line naming `option`
/// (the front end's name of the list) for anything else: an empty item, a sign, a fraction, nan or inf, a number
/// too large, a reversed range, too many seeds, a seed given twice.
[[nodiscard]] std::vector<std::uint64_t> parseSeedList(const std::string& option, const std::string& text);

/// readInput("threads", text) as an int.
[[nodiscard]] int readThreads(std::string_view text);

}  // namespace archipelago
