#include "core/measures/IndicatorKind.hpp"

namespace archipelago {

namespace {
constexpr IndicatorKind kKinds[] = {IndicatorKind::Dig, IndicatorKind::Rotation, IndicatorKind::Fli,
                                    IndicatorKind::Megno, IndicatorKind::Lyapunov};
}  // namespace

std::string_view toString(IndicatorKind kind) noexcept {
  switch (kind) {
    case IndicatorKind::Dig: return "dig";
    case IndicatorKind::Rotation: return "rotation";
    case IndicatorKind::Fli: return "fli";
    case IndicatorKind::Megno: return "megno";
    case IndicatorKind::Lyapunov: return "lyapunov";
  }
  return "unknown";
}

std::optional<IndicatorKind> parseIndicatorKind(std::string_view name) noexcept {
  for (IndicatorKind k : kKinds)
    if (name == toString(k)) return k;
  return std::nullopt;
}

std::string indicatorKindNames() {
  std::string s;
  for (IndicatorKind k : kKinds) s += (s.empty() ? "" : ", ") + std::string(toString(k));
  return s;
}

bool isBirkhoffKind(IndicatorKind kind) noexcept { return kind == IndicatorKind::Dig || kind == IndicatorKind::Rotation; }

}  // namespace archipelago
