#pragma once
/// \file RangeCheck.hpp
/// \brief The one-line error of a request field outside its range, as the portrait and b₂ validations word it.

#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

namespace archipelago {

/// "name = value must be lo ... hi" when the integer value lies outside [lo, hi], else nothing.  `highText`
/// replaces hi in the message when given (e.g. "2^20").
template <class T>
[[nodiscard]] std::optional<std::string> outsideRange(std::string_view name, T value, long long lo, long long hi,
                                                      std::string_view highText = {}) {
  if (std::cmp_greater_equal(value, lo) && std::cmp_less_equal(value, hi)) return std::nullopt;
  std::ostringstream s;
  s << name << " = " << value << " must be " << lo << " ... ";
  if (highText.empty()) s << hi; else s << highText;
  return s.str();
}

}  // namespace archipelago
