#include "core/runspec/InputRules.hpp"

#include <array>
#include <stdexcept>

#include "core/io/NumberText.hpp"

namespace archipelago {

namespace {
const std::array<ParameterRule, 1> kSettings{{
    {"threads", "worker threads (0: one per core); results do not depend on it", true, 0,
     static_cast<std::uint64_t>(kMaxThreads), "[0, 256] (0: one per core)"},
}};
static_assert(limits::kThreads == 256, "the range text of kSettings says 256");
}  // namespace

std::span<const ParameterRule> settingRules() noexcept { return kSettings; }

const ParameterRule* findInputRule(std::string_view key) noexcept {
  if (const ParameterRule* r = findParameterRule(key)) return r;
  for (const ParameterRule& r : kSettings)
    if (r.key == key) return &r;
  return nullptr;
}

ParameterValue readInput(std::string_view key, std::string_view text) {
  const ParameterRule* rule = findInputRule(key);
  if (rule == nullptr) throw std::invalid_argument("unknown input '" + io::shortText(key) + "'");
  if (rule->integer) {
    const std::optional<std::uint64_t> v = io::toNumber<std::uint64_t>(text);
    if (!v)
      throw std::invalid_argument(std::string(key) + " = " + io::shortText(text) + " must be a whole number in " +
                                  std::string(rule->range));
    // A parameter's range is validationErrors()'s rule (one message: "must lie in"); a setting's is checked here.
    if (findParameterRule(key) == nullptr && (*v < rule->min || *v > rule->max))
      throw std::invalid_argument(std::string(key) + " = " + std::to_string(*v) + " must lie in " +
                                  std::string(rule->range));
    return *v;
  }
  const std::optional<double> v = io::toNumber<double>(text);
  if (!v) throw std::invalid_argument(std::string(key) + " = " + io::shortText(text) + " must be a finite number");
  return *v;
}

int readThreads(std::string_view text) { return static_cast<int>(std::get<std::uint64_t>(readInput("threads", text))); }

}  // namespace archipelago
