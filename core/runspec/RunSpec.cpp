#include "core/runspec/RunSpec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/io/AtomicFile.hpp"
#include "core/io/Json.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/runspec/RunSpecJson.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

using nlohmann::json;

[[noreturn]] void bad(const std::string& what) { throw io::BadFile(what); }

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
  const io::JsonField parameters(j, "parameters");
  parameters.object();
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!findParameterRule(it.key())) bad("unknown parameter '" + io::shortText(it.key()) + "'");
  TrappingParameters p = defaults;
  for (const ParameterRule& r : parameterRules()) {
    const auto v = parameters.find(r.key);
    if (!v) {
      if (complete) bad("missing parameter '" + std::string(r.key) + "'");
      continue;
    }
    try {  // throws "<key> = v must lie in <range>" outside the documented range
      if (r.integer) setParameterValue(p, r.key, v->wholeOrExactReal(std::numeric_limits<std::uint64_t>::max()));
      else setParameterValue(p, r.key, v->real());
    } catch (const std::invalid_argument& e) {
      bad(e.what());
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
    if (auto e = realIntervalError("companion", s.companion, 0, true, 1, "the fraction of the run's steps")) return e;
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
  const io::JsonField root(j, "the run spec");
  root.keys({}, {"format", "version", "name", "description", "parameters", "kernel", "threads", "companion"});
  RunSpec s;
  if (const auto name = root.find("name")) s.name = name->string(200);
  if (const auto description = root.find("description")) s.description = description->string(4000);
  if (const auto p = root.find("parameters")) s.parameters = spec::parametersFromJson(p->value(), false);
  if (const auto kernel = root.find("kernel")) s.kernel = kernel->string(64);
  if (const auto t = root.find("threads")) s.threads = static_cast<int>(t->wholeOrExactReal(kMaxThreads));
  if (const auto c = root.find("companion")) s.companion = c->real();
  if (auto e = validationError(s)) bad(*e);
  return s;
}

RunSpec loadRunSpec(const std::filesystem::path& path) {
  constexpr std::uintmax_t kMaxSpecBytes = 1 << 20;  // a spec is a few hundred bytes
  std::string content;
  try {
    content = io::readRegularFile(path, kMaxSpecBytes);
  } catch (const std::runtime_error& e) {  // its message names the path
    bad(e.what());
  }
  try {
    return parseRunSpec(content);
  } catch (const io::BadFile& e) {
    bad(path.string() + ": " + e.what());
  }
}

}  // namespace archipelago
