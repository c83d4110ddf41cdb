#include "core/runspec/RunSpec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <vector>

#include "core/io/AtomicFile.hpp"
#include "core/io/Json.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/runspec/RunSpecJson.hpp"

namespace archipelago {

namespace {

using nlohmann::json;

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(what); }

/// A JSON value that is a whole number in [0, max]: an integer, or a real that is exactly such a number
/// (hand-written specs may say 2e7).
std::uint64_t wholeNumber(const json& v, std::string_view key, std::uint64_t max) {
  std::uint64_t n = 0;
  if (v.is_number_unsigned()) {
    n = v.get<std::uint64_t>();
  } else if (v.is_number_integer()) {
    bad(std::string(key) + " = " + io::describeJson(v) + " must be a whole number in [0, " + std::to_string(max) + "]");
  } else if (v.is_number_float()) {
    const double d = v.get<double>();
    // 2^64 is the first double past the range of std::uint64_t.
    if (!(d >= 0 && d < 18446744073709551616.0) || std::floor(d) != d)
      bad(std::string(key) + " = " + io::describeJson(v) + " must be a whole number in [0, " + std::to_string(max) + "]");
    n = static_cast<std::uint64_t>(d);
  } else {
    bad(std::string(key) + " must be a number, not " + io::describeJson(v));
  }
  if (n > max) bad(std::string(key) + " = " + std::to_string(n) + " must be <= " + std::to_string(max));
  return n;
}

double realNumber(const json& v, std::string_view key) {
  if (!v.is_number()) bad(std::string(key) + " must be a number, not " + io::describeJson(v));
  return v.get<double>();
}

std::string text(const json& j, const char* key, std::size_t maxBytes) {
  const auto it = j.find(key);
  if (it == j.end()) return {};
  if (!it->is_string()) bad(std::string(key) + " must be a string, not " + io::describeJson(*it));
  std::string s = it->get<std::string>();
  if (s.size() > maxBytes) bad(std::string(key) + " is longer than " + std::to_string(maxBytes) + " bytes");
  return s;
}

}  // namespace

namespace spec {

json mapJson(const MapParameters& map) { return {{"K", map.K}, {"xmin", map.xmin}, {"xmax", map.xmax}}; }

json parametersJson(const TrappingParameters& p) {
  json j = json::object();
  for (const ParameterRule& r : parameterRules()) {
    const ParameterValue v = parameterValue(p, r.key);
    if (const auto* real = std::get_if<double>(&v)) j[std::string(r.key)] = *real;
    else j[std::string(r.key)] = std::get<std::uint64_t>(v);
  }
  return j;
}

TrappingParameters parametersFromJson(const json& j, bool complete, const TrappingParameters& defaults) {
  if (!j.is_object()) bad("parameters must be a JSON object");
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!findParameterRule(it.key())) bad("unknown parameter '" + io::shortText(it.key()) + "'");
  TrappingParameters p = defaults;
  for (const ParameterRule& r : parameterRules()) {
    const std::string key(r.key);
    const auto it = j.find(key);
    if (it == j.end()) {
      if (complete) bad("missing parameter '" + key + "'");
      continue;
    }
    if (r.integer) {
      const std::uint64_t v = wholeNumber(*it, key, std::numeric_limits<std::uint64_t>::max());
      setParameterValue(p, r.key, v);  // throws "<key> = v must lie in <range>" outside the documented range
    } else {
      setParameterValue(p, r.key, realNumber(*it, key));
    }
  }
  return p;
}

void checkVersionedDocument(const json& j, const char* format, int version, const std::string& article,
                            const std::string& what) {
  if (!j.is_object()) bad(article + " " + what + " must be a JSON object");
  const auto f = j.find("format");
  if (f == j.end() || *f != format) bad("not " + article + " " + what + " (missing \"format\": \"" + format + "\")");
  const auto v = j.find("version");
  if (v == j.end() || !v->is_number_unsigned() || v->get<std::uint64_t>() != static_cast<std::uint64_t>(version))
    bad(what + " version " + (v == j.end() ? std::string("(missing)") : io::describeJson(*v)) +
        " is not supported (this program reads version " + std::to_string(version) + ")");
}

json parseVersionedDocument(std::string_view text, const char* format, int version, const std::string& article,
                            const std::string& what) {
  json j = io::parseJson(text);
  checkVersionedDocument(j, format, version, article, what);
  return j;
}

}  // namespace spec

std::optional<std::string> validationError(const RunSpec& s) {
  if (auto e = validationError(s.parameters)) return e;
  if (s.kernel != "auto") {
    const auto kernels = allKernels();
    const bool known =
        std::any_of(kernels.begin(), kernels.end(), [&](const KernelInfo& k) { return k.name == s.kernel; });
    if (!known) {
      std::string names = "auto";
      for (const KernelInfo& k : kernels) names += ", " + std::string(k.name);
      return "kernel = '" + io::shortText(s.kernel) + "' is not a kernel (" + names + ")";
    }
  }
  if (auto e = threadsError(s.threads)) return e;
  if (s.companion != 0) {
    if (!(s.companion > 0 && s.companion <= 1))
      return "companion = " + io::shortestText(s.companion) + " must lie in (0, 1] (the fraction of the run's steps)";
    if (s.parameters.q <= 1) return "companion: a run of q = 1 needs no q = 1 companion (remove it)";
  }
  return std::nullopt;
}

std::string runSpecJson(const RunSpec& s) {
  json j = json::object();
  j["format"] = kRunSpecFormatName;
  j["version"] = kRunSpecFormatVersion;
  if (!s.name.empty()) j["name"] = s.name;
  if (!s.description.empty()) j["description"] = s.description;
  j["parameters"] = spec::parametersJson(s.parameters);
  j["kernel"] = s.kernel;
  j["threads"] = s.threads;
  if (s.companion != 0) j["companion"] = s.companion;
  return j.dump(2) + "\n";
}

RunSpec parseRunSpec(std::string_view textIn) {
  const json j = spec::parseVersionedDocument(textIn, kRunSpecFormatName, kRunSpecFormatVersion, "a", "run spec");
  for (auto it = j.begin(); it != j.end(); ++it) {
    static const std::set<std::string> known{"format", "version", "name", "description", "parameters", "kernel", "threads",
                                             "companion"};
    if (!known.count(it.key())) bad("unknown key '" + io::shortText(it.key()) + "'");
  }
  RunSpec s;
  s.name = text(j, "name", 200);
  s.description = text(j, "description", 4000);
  if (const auto p = j.find("parameters"); p != j.end()) s.parameters = spec::parametersFromJson(*p, false);
  if (j.contains("kernel")) s.kernel = text(j, "kernel", 64);
  if (const auto t = j.find("threads"); t != j.end())
    s.threads = static_cast<int>(wholeNumber(*t, "threads", kMaxThreads));
  if (const auto c = j.find("companion"); c != j.end()) s.companion = realNumber(*c, "companion");
  if (auto e = validationError(s)) bad(*e);
  return s;
}

RunSpec loadRunSpec(const std::filesystem::path& path) {
  constexpr std::uintmax_t kMaxSpecBytes = 1 << 20;  // a spec is a few hundred bytes
  std::string content;
  try {
    content = io::readRegularFile(path, kMaxSpecBytes);
  } catch (const std::runtime_error& e) {
    bad(e.what());
  }
  try {
    return parseRunSpec(content);
  } catch (const std::invalid_argument& e) {
    bad(path.string() + ": " + e.what());
  }
}

}  // namespace archipelago
