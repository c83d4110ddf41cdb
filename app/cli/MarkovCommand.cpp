#include "MarkovCommand.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "CliCommon.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/markov/MarkovModel.hpp"

namespace archipelago::cli {

namespace {
struct MarkovOptions {
  std::string lengths;
  std::string points;
  std::string tauMax;
  std::string csv;
};

[[noreturn]] void reject(const std::string& option, const std::string& value, const std::string& requirement) {
  throw std::invalid_argument(option + " = " + value + " must be " + requirement);
}

/// A whole number in [low, high], read by the CLI's one number parser (CliCommon.hpp); anything else is
/// rejected, naming the option and its whole value `shown`.
std::int64_t parseWhole(const std::string& option, const std::string& text, const std::string& shown,
                        std::int64_t low, std::int64_t high, const std::string& requirement) {
  const std::optional<std::int64_t> v = toNumber<std::int64_t>(text);
  if (!v || *v < low || *v > high) reject(option, shown, requirement);
  return *v;
}

std::vector<std::int64_t> parseLengths(const std::string& text) {
  const std::string requirement = "a comma-separated list of whole numbers 1 ... " +
                                  std::to_string(markov::MarkovModel::kMaxTrappedPoints) + " with a total <= " +
                                  std::to_string(markov::MarkovModel::kMaxTrappedPoints);
  std::vector<std::int64_t> lengths;
  std::int64_t total = 0;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = text.find(',', begin);
    const std::string item = text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    lengths.push_back(parseWhole("--m", item, text, 1, markov::MarkovModel::kMaxTrappedPoints, requirement));
    total += lengths.back();
    if (total > markov::MarkovModel::kMaxTrappedPoints) reject("--m", text, requirement);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return lengths;
}

int runMarkov(const MarkovOptions& o) {
  markov::MarkovModel model;
  model.segmentLengths = parseLengths(o.lengths);
  const std::int64_t m = model.trappedPoints();
  const auto M = static_cast<std::int64_t>(model.segmentLengths.size());
  model.points = parseWhole("--N", o.points, o.points, m + M + 1, markov::MarkovModel::kMaxPoints,
                            "a whole number m + M + 1 = " + std::to_string(m + M + 1) +
                                " ... 2^53 (at least one sea point besides the pre-images)");
  const std::int64_t tauMax =
      o.tauMax.empty() ? std::min(4 * m, markov::maxTau(model))
                       : parseWhole("--tau-max", o.tauMax, o.tauMax, 0, std::numeric_limits<std::int64_t>::max(),
                                    "a whole number");
  if (auto e = markov::seriesError(model, tauMax)) throw std::invalid_argument(*e);  // core's rule and message
  io::checkCommandFiles({{"--csv", o.csv, io::FileUse::Output}});  // before any work: a bad path fails at once
  markov::checkSeriesMemory(tauMax);  // the three series at once, before the first (issue #23)

  const markov::LumpedObservable h = markov::paperObservable(model);
  const double D = markov::diffusionCoefficient(model, h);
  const double Dmark = markov::diffusionCoefficientDmark(model, h);
  const double Dis = markov::islandDiffusionCoefficient(model);
  const double sea = h.freeSeaSquares / (2 * static_cast<double>(model.points));
  const std::vector<double> C = markov::correlation(model, h, tauMax);
  const std::vector<double> Cis = markov::islandCorrelation(model, tauMax);
  const std::vector<double> eps = markov::correlationDeviation(model, h, tauMax);

  std::printf("# Markov model of Karney (1983), appendix C\n");
  std::printf("# segments: %s (M = %lld, m = %lld)\n", o.lengths.c_str(), static_cast<long long>(M),
              static_cast<long long>(m));
  std::printf("# N: %lld\n", static_cast<long long>(model.points));
  std::printf("# observable: h = 1 on T, 0 on the pre-images, %.17g on the other %lld sea points\n",
              -static_cast<double>(m) / static_cast<double>(model.freeSeaPoints()),
              static_cast<long long>(model.freeSeaPoints()));
  std::printf("# D_matrix: %.17g (h.(I/2 + Q(I - Q)^-1).h/N)\n", D);
  std::printf("# D_dmark: %.17g (eq. dmark)\n", Dmark);
  std::printf("# D_island: %.17g (D - sum_{S'} h^2/2N; D_is = sum m_k^2/2N = %.17g)\n", D - sea, Dis);
  std::ostringstream out;
  out.precision(17);
  out << "tau,C,C_is,epsilon\n";
  for (std::size_t t = 0; t < C.size(); ++t) out << t << ',' << C[t] << ',' << Cis[t] << ',' << eps[t] << '\n';
  if (o.csv.empty()) {
    std::fputs(out.str().c_str(), stdout);
  } else {
    io::writeFileAtomically(o.csv, out.str());
    std::printf("# wrote: %s (tau, C, C_is, epsilon for tau = 0 ... %lld)\n", o.csv.c_str(),
                static_cast<long long>(tauMax));
  }
  return 0;
}
}  // namespace

void addMarkovCommand(CLI::App& app, int& status) {
  auto options = std::make_shared<MarkovOptions>();
  CLI::App* cmd = app.add_subcommand(
      "markov", "Markov model of appendix C: D by the matrix formula and eq. (dmark); tau, C, C_is, epsilon as CSV");
  cmd->add_option("--m", options->lengths, "trapped-segment lengths m_k, comma-separated (1 ... 1e6 in total)")
      ->required();
  cmd->add_option("--N", options->points, "number of points N (m + M + 1 ... 2^53)")->required();
  cmd->add_option("--tau-max", options->tauMax, "largest lag tau (default 4m; at most 5e8/(m + 1) - 1)");
  cmd->add_option("--csv", options->csv, "write the CSV to this file instead of stdout");
  cmd->callback([options, &status] { status = runMarkov(*options); });
}

}  // namespace archipelago::cli
