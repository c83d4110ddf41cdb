#include "core/trapping/TrappingParameters.hpp"

#include "core/io/Memory.hpp"

#include "core/random/CounterRng.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/trapping/TrappingHistogram.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

struct Access {
  ParameterRule rule;
  double MapParameters::*mapReal = nullptr;     // K, xmin, xmax
  double TrappingParameters::*real = nullptr;   // Xr
  std::uint32_t TrappingParameters::*u32 = nullptr;
  std::uint64_t TrappingParameters::*u64 = nullptr;
};

constexpr std::uint64_t kU64Max = ~std::uint64_t{0};

const std::array<Access, 10>& accessTable() {
  static const std::array<Access, 10> table{{
      {{"K", "map parameter K of Q: y′ = y + 2(x² − K), x′ = x + y′ (§2)", false, 0, 0, "finite"},
       &MapParameters::K},
      {{"xmin", "left edge of the box in x (appendix B)", false, 0, 0, "finite, < −√K (K ≥ 0) or < 0 (K < 0)"},
       &MapParameters::xmin},
      {{"xmax", "right edge of the box in x", false, 0, 0, "finite, > xmin"}, &MapParameters::xmax},
      {{"Xr", "randomizing zone 0 ≤ X ≤ Xr in unit coordinates (appendix B)", false, 0, 0, "[0, 1)"}, nullptr,
       &TrappingParameters::Xr},
      {{"q", "steps of N⁻¹ per block: statistics of the q-th power of N⁻¹ (appendix B)", true, 1, kMaxQ, "[1, 65536]"}, nullptr,
       nullptr, &TrappingParameters::q},
      {{"T", "blocks per orbit (each orbit is q·T steps)", true, 1, kMaxT, "[1, 2⁶²], q·T ≤ 2⁶²"}, nullptr, nullptr,
       nullptr, &TrappingParameters::T},
      {{"M", "number of orbits", true, 1, kMaxM, "[1, 2³²] (and the memory they need)"}, nullptr, nullptr, nullptr,
       &TrappingParameters::M},
      {{"seed", "seed of the counter-based random numbers", true, 0, kU64Max, "[0, 2⁶⁴ − 1]"}, nullptr, nullptr,
       nullptr, &TrappingParameters::seed},
      {{"subsets", "orbit subsets for error estimates (orbit i goes to subset i mod subsets)", true, 1, kMaxSubsets,
        "[1, 1024], ≤ M"},
       nullptr, nullptr, &TrappingParameters::subsets},
      {{"longestKept", "longest segments kept with their start state, for replay", true, 0, kMaxLongestKept,
        "[0, 100000]"},
       nullptr, nullptr, &TrappingParameters::longestKept},
  }};
  return table;
}

const Access& access(std::string_view key) {
  for (const Access& a : accessTable())
    if (a.rule.key == key) return a;
  throw std::invalid_argument("unknown parameter '" + std::string(key) + "'");
}

}  // namespace

std::span<const ParameterRule> parameterRules() noexcept {
  static const std::vector<ParameterRule> rules = [] {
    std::vector<ParameterRule> v;
    for (const Access& a : accessTable()) v.push_back(a.rule);
    return v;
  }();
  return rules;
}

const ParameterRule* findParameterRule(std::string_view key) noexcept {
  for (const ParameterRule& r : parameterRules())
    if (r.key == key) return &r;
  return nullptr;
}

ParameterValue parameterValue(const TrappingParameters& p, std::string_view key) {
  const Access& a = access(key);
  if (a.mapReal) return p.map.*a.mapReal;
  if (a.real) return p.*a.real;
  if (a.u32) return std::uint64_t{p.*a.u32};
  return p.*a.u64;
}

void setParameterValue(TrappingParameters& p, std::string_view key, const ParameterValue& value) {
  const Access& a = access(key);
  if (a.rule.integer != std::holds_alternative<std::uint64_t>(value))
    throw std::invalid_argument(std::string(key) + (a.rule.integer ? " must be a whole number" : " must be a real number"));
  if (!a.rule.integer) {
    (a.mapReal ? p.map.*a.mapReal : p.*a.real) = std::get<double>(value);
    return;
  }
  // A value the member cannot hold is refused here, never narrowed; the rest of the range (q >= 1, M <= 2^32,
  // …) is validationError()'s, so that each rule has one message.
  const std::uint64_t v = std::get<std::uint64_t>(value);
  if (a.u32 && v > a.rule.max)
    throw std::invalid_argument(wholeRangeError(key, std::to_string(v), a.rule.range));
  if (a.u32) p.*a.u32 = static_cast<std::uint32_t>(v);
  else p.*a.u64 = v;
}

TrappingParameters companionParameters(const TrappingParameters& p, double fraction) {
  if (p.q <= 1) throw std::invalid_argument("a run of q = 1 needs no q = 1 companion");
  if (auto e = realIntervalError("companion", fraction, 0, true, 1, "the fraction of the run's steps"))
    throw std::invalid_argument(*e);
  TrappingParameters c = p;
  c.q = 1;
  const long double steps = static_cast<long double>(fraction) * p.q * static_cast<long double>(p.T);
  c.T = steps < 1 ? 1 : static_cast<std::uint64_t>(std::llround(static_cast<double>(steps)));
  c.seed = mix64(p.seed ^ kCompanionSeedSalt);
  return c;
}

std::uint64_t estimatedMemoryBytes(const TrappingParameters& p, int threads) noexcept {
  const long cores = ::sysconf(_SC_NPROCESSORS_ONLN);
  const double workers = static_cast<double>(threads > 0 ? threads : std::max(1L, cores));
  // The state, and what writing it as a run file takes (issue #23: measured ~730 bytes per orbit of resident
  // memory while saving: the JSON document, its text for the checksum and the text written).
  const double orbits = static_cast<double>(p.M) * (sizeof(OrbitState) + kSaveBytesPerOrbit);
  const double histograms = static_cast<double>(p.subsets) * (workers + 2) * sizeof(TrappingHistogram);
  const double longest = static_cast<double>(p.longestKept) * (workers + 2) * (sizeof(SegmentRecord) + 200.0);
  const double total = orbits + histograms + longest;
  return total >= 1.8e19 ? ~std::uint64_t{0} : static_cast<std::uint64_t>(total);
}

std::optional<std::string> memoryError(const TrappingParameters& p, int threads) {
  // A run whose file could not be read back is refused too (issue #23: a very large M wrote files above the cap).
  const double fileBytes = static_cast<double>(p.M) * kRunFileBytesPerOrbit + static_cast<double>(p.longestKept) * 300.0;
  if (fileBytes > static_cast<double>(kMaxRunFileBytes)) {
    std::ostringstream s;
    s.imbue(std::locale::classic());
    s.precision(3);
    s << "M = " << p.M << " orbits would make a run file of up to " << fileBytes / 1e9 << " GB, more than the "
      << static_cast<double>(kMaxRunFileBytes) / 1e9
      << " GB a run file may hold: split the orbits over several runs (a range of orbits each) and merge their statistics";
    return s.str();
  }
  // What this process may still take (core/io's one definition: MemAvailable and what RLIMIT_AS leaves).
  const double available = static_cast<double>(io::availableMemoryBytes());
  const double need = static_cast<double>(estimatedMemoryBytes(p, threads));
  if (need <= available) return std::nullopt;
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s.precision(3);
  s << "the run needs about " << need / 1e9 << " GB of memory (M = " << p.M << " orbits, subsets = " << p.subsets
    << ", longestKept = " << p.longestKept << ") but only " << available / 1e9 << " GB are available";
  return s.str();
}

std::vector<ParameterError> validationErrors(const TrappingParameters& p) {
  std::vector<ParameterError> errors = mapErrors(p.map);
  if (auto e = randomizingZoneError(p.Xr)) errors.push_back({{"Xr"}, std::move(*e)});
  bool integersInRange = true;
  for (const ParameterRule& r : parameterRules()) {  // the documented range of every integer
    if (!r.integer) continue;
    const std::uint64_t v = std::get<std::uint64_t>(parameterValue(p, r.key));
    if (v < r.min || v > r.max) {
      errors.push_back({{std::string(r.key)}, wholeRangeError(r.key, std::to_string(v), r.range)});
      integersInRange = false;
    }
  }
  if (p.q >= 1 && p.q <= kMaxQ && p.T >= 1 && p.T <= kMaxT && p.T > kMaxStepsPerOrbit / p.q)
    errors.push_back({{"T", "q"}, "q·T = " + std::to_string(p.q) + "·" + std::to_string(p.T) + " must be ≤ 2⁶² (steps per orbit)"});
  if (integersInRange && p.subsets > p.M)
    errors.push_back({{"subsets", "M"}, "subsets = " + std::to_string(p.subsets) + " must be ≤ M = " + std::to_string(p.M) +
                                            " (each subset needs an orbit)"});
  return errors;
}

std::optional<std::string> validationError(const TrappingParameters& p) {
  auto errors = validationErrors(p);
  if (errors.empty()) return std::nullopt;
  return std::move(errors.front().message);
}

void validate(const TrappingParameters& p) {
  if (auto e = validationError(p)) throw std::invalid_argument(*e);
}

std::optional<std::string> randomizingZoneError(double Xr) {
  if (std::isfinite(Xr) && Xr >= 0 && Xr < 1) return std::nullopt;
  return "Xr = " + shortestDecimal(Xr) + " must lie in [0, 1) (width of the randomizing zone in unit X)";
}

std::uint64_t randomizingThreshold(double Xr) noexcept {
  // Defined for every double: a NaN, negative or huge Xr converted to an integer is undefined behaviour (clang's
  // UBSan found `portrait --Xr 1e308` in density mode, where Xr is not used, reaching this conversion).  Callers
  // validate Xr (randomizingZoneError) first; here NaN and Xr ≤ 0 give 0, Xr ≥ 1 the whole unit 2^52.
  if (!(Xr > 0)) return 0;
  if (Xr >= 1) return std::uint64_t{1} << FixedPointMap::kBits;
  return static_cast<std::uint64_t>(std::floor(std::ldexp(Xr, FixedPointMap::kBits)));
}

OrbitStateRow orbitStateRow(const OrbitState& o) noexcept {
  return {o.z.X, o.z.Y, o.block, o.draws, o.length, o.start.z.X, o.start.z.Y, o.start.block, o.start.draws};
}

OrbitState orbitStateOfRow(const OrbitStateRow& r) noexcept {
  return {{r[0], r[1]}, r[2], r[3], r[4], {{r[5], r[6]}, r[7], r[8]}};
}

std::uint64_t orbitStateRowMax(std::size_t column) noexcept {
  const bool coordinate = column == 0 || column == 1 || column == 5 || column == 6;
  return coordinate ? FixedPointMap::kOne - 1 : UINT64_MAX;
}

}  // namespace archipelago
