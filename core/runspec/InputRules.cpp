#include "core/runspec/InputRules.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"

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
      throw std::invalid_argument(wholeRangeError(key, std::to_string(*v), rule->range));
    return *v;
  }
  const std::optional<double> v = io::toNumber<double>(text);
  if (!v) throw std::invalid_argument(std::string(key) + " = " + io::shortText(text) + " must be a finite number");
  return *v;
}

int readThreads(std::string_view text) { return static_cast<int>(std::get<std::uint64_t>(readInput("threads", text))); }

std::vector<std::uint64_t> parseSeedList(const std::string& option, const std::string& text) {
  constexpr std::uint64_t kMaxSeeds = limits::kSeeds;
  const ParameterRule* rule = findParameterRule("seed");
  const std::string what = option + " = " + text + " must be seeds K or ranges A..B separated by commas, integers in [" +
                           std::to_string(rule->min) + ", " + std::to_string(rule->max) + "]";
  std::vector<std::uint64_t> seeds;
  std::string_view rest = text;
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    const std::size_t dots = item.find("..");
    const std::optional<std::uint64_t> first = io::toNumber<std::uint64_t>(item.substr(0, dots));
    const std::optional<std::uint64_t> last =
        dots == std::string_view::npos ? first : io::toNumber<std::uint64_t>(item.substr(dots + 2));
    if (!first || !last || *first < rule->min || *last > rule->max) throw std::invalid_argument(what);
    if (*first > *last) throw std::invalid_argument(option + " = " + text + ": the range " + std::string(item) + " is reversed");
    if (*last - *first >= kMaxSeeds || seeds.size() + (*last - *first) >= kMaxSeeds)
      throw std::invalid_argument(option + " = " + text + " asks for more than " + std::to_string(kMaxSeeds) + " seeds");
    for (std::uint64_t s = *first;; ++s) {
      if (std::find(seeds.begin(), seeds.end(), s) != seeds.end())
        throw std::invalid_argument(option + " = " + text + " gives seed " + std::to_string(s) + " twice");
      seeds.push_back(s);
      if (s == *last) break;
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return seeds;
}

}  // namespace archipelago
