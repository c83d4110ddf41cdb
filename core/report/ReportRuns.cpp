#include "core/report/ReportRuns.hpp"

#include <cmath>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/scan/ScanBox.hpp"
#include "core/runspec/RunSpec.hpp"

namespace archipelago::report {

namespace {

const RunSpec& presetSpec(const char* id) {
  const Preset* p = findPreset(id);
  if (p == nullptr) throw std::logic_error(std::string("preset missing: ") + id);
  return p->spec;
}

std::string parameterOptions(const TrappingParameters& p) {
  return io::formatC("--K %s --xmin=%s --xmax %s --q %u --T %llu --M %llu --seed %llu", io::shortestText(p.map.K).c_str(),
                     io::shortestText(p.map.xmin).c_str(), io::shortestText(p.map.xmax).c_str(), p.q,
                     static_cast<unsigned long long>(p.T), static_cast<unsigned long long>(p.M),
                     static_cast<unsigned long long>(p.seed));
}

ReportRun run(const TrappingParameters& p, std::string file) {
  return {p, file, cliCommand("run " + parameterOptions(p) + " --out " + file)};
}

}  // namespace

const char* sizeName(ReportSize size) noexcept { return size == ReportSize::full ? "full" : "quick"; }

std::string cliCommand(const std::string& rest) { return "archipelago-cli " + rest; }
std::string onlyCommand(std::string_view id) { return "archipelago-reproduce --only " + std::string(id) + " OUTDIR"; }

ReportRun k01Run(ReportSize size) {
  TrappingParameters p;
  if (size == ReportSize::full) {
    p = presetSpec("k0.1-paper-fig6").parameters;
  } else {
    p = presetSpec("k0.1-minute").parameters;
    p.T /= 40;
    p.M /= 2;
  }
  return run(p, std::string("k01-") + sizeName(size) + ".json");
}

ReportRun k01CompanionRun(ReportSize size) {
  const RunSpec& spec = presetSpec(size == ReportSize::full ? "k0.1-paper-fig6" : "k0.1-minute");
  const TrappingParameters p = companionParameters(k01Run(size).params, spec.companion);
  return run(p, std::string("k01-") + sizeName(size) + ".short.json");
}

TailRequest tailSamplerRequest(ReportSize size) {
  TailRequest r;
  r.run = k01Run(size).params;
  r.population = size == ReportSize::full ? 800 : 100;
  r.replicas = size == ReportSize::full ? 16 : 8;
  r.maxSteps = size == ReportSize::full ? 10'000'000 : 1'000'000;
  return r;
}

std::string tailSamplerCommand(ReportSize size) {
  const TailRequest r = tailSamplerRequest(size);
  return cliCommand(io::formatC("tail --preset %s --population %u --replicas %u --t-max %llu --out tail.json "
                                "--compare %s",
                                size == ReportSize::full ? "k0.1-paper-fig6" : "k0.1-minute", r.population, r.replicas,
                                static_cast<unsigned long long>(r.maxSteps), k01Run(size).file.c_str()));
}

AtlasRequest k01AtlasRequest(ReportSize size) {
  AtlasRequest r;
  r.map = k01Run(size).params.map;
  r.depth = size == ReportSize::full ? 2 : 1;
  return r;
}

std::string k01AtlasFile(ReportSize size) { return std::string("atlas-") + sizeName(size) + ".json"; }

std::string markovTreeCommand(ReportSize size, double alpha, double b2) {
  const AtlasRequest a = k01AtlasRequest(size);
  const std::string file = k01AtlasFile(size);
  return cliCommand(io::formatC("atlas --K %s --xmin=%s --xmax %s --depth %d --json %s", io::shortestText(a.map.K).c_str(),
                                io::shortestText(a.map.xmin).c_str(), io::shortestText(a.map.xmax).c_str(), a.depth,
                                file.c_str())) +
         " && " + tailSamplerCommand(size) + " && " +
         cliCommand(io::formatC("markov-tree --atlas %s --tail tail.json --alpha %s --b2 %s", file.c_str(),
                                io::shortestText(alpha).c_str(), io::shortestText(b2).c_str()));
}

ReportRun smallKRun(char panel, ReportSize size) {
  const char* id = panel == 'a' ? "small-k-negative" : panel == 'b' ? "small-k-zero" : "small-k-positive";
  TrappingParameters p = presetSpec(id).parameters;
  if (size == ReportSize::quick) p.T /= 10;
  return run(p, std::string("smallk") + panel + "-" + sizeName(size) + ".json");
}

ReportRun decayRun(double K, ReportSize size) {
  TrappingParameters p = smallKRun('c', size).params;
  const double half = 5 * std::sqrt(K);  // the preset's box is ±5√K at K = 10⁻⁴
  p.map = {K, -half, half};
  return run(p, "decay-" + io::shortestText(K) + "-" + sizeName(size) + ".json");
}

KScanRequest kScanRequest(ReportSize size, const std::filesystem::path& dir) {
  KScanRequest r;
  r.K = parseScanValues(kPaperScanValuesText);
  r.dir = dir;
  r.base.parameters.q = 16;
  r.base.parameters.M = 64;
  r.base.parameters.T = size == ReportSize::full ? 5'000'000 : 200'000;
  r.base.parameters.seed = 1983;
  return r;
}

std::string kScanCommand(ReportSize size) {
  const KScanRequest r = kScanRequest(size, "scan");
  return cliCommand("scan --K " + std::string(kPaperScanValuesText) + " --q " + std::to_string(r.base.parameters.q) +
                    " --M " + std::to_string(r.base.parameters.M) + " --T " + std::to_string(r.base.parameters.T) +
                    " --seed " + std::to_string(r.base.parameters.seed) + " --dir scan");
}

TailScanRequest tailScanRequest(ReportSize size, const std::filesystem::path& dir) {
  const bool full = size == ReportSize::full;
  TailScanRequest r;
  r.K = full ? "0.05:0.25:0.01" : "0.1,0.15,0.2";
  r.request.population = full ? 800 : 400;
  r.request.replicas = full ? 16 : 8;
  r.request.maxSteps = 1'000'000;
  r.dir = dir.string();
  return r;
}

std::string tailScanCommand(ReportSize size) {
  const TailScanRequest r = tailScanRequest(size, "tailscan");
  return cliCommand(io::formatC("tail-scan --K %s --population %u --replicas %u --t-max %llu --dir %s", r.K.c_str(),
                                r.request.population, r.request.replicas,
                                static_cast<unsigned long long>(r.request.maxSteps), r.dir.c_str()));
}

MapParameters paperSizedBox() { return {0.1, -0.7, 0.3}; }

StochasticAreaRequest stochasticAreaRequest(ReportSize size, const MapParameters& box) {
  StochasticAreaRequest r;
  r.map = box;
  r.iterations = size == ReportSize::full ? (1ULL << 30) : (1ULL << 27);
  return r;
}

}  // namespace archipelago::report
