#include "CantorusCommand.hpp"

#include <chrono>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "CliCommon.hpp"
#include "RunSession.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/manifolds/MmpFlux.hpp"
#include "core/manifolds/QuadText.hpp"

namespace archipelago::cli {

namespace {
struct CantorusOptions {
  MapParameters map;
  std::string convergents;
  CantorusRequest request;
  bool json = false;
  std::string out;
};

/// "5/31,6/37,…": each p and q a whole number read by the CLI's one parser (their range is core's rule).
std::vector<std::pair<long, int>> parseConvergents(const std::string& text) {
  std::vector<std::pair<long, int>> list;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = text.find(',', begin);
    const std::string item = text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    const std::size_t slash = item.find('/');
    const auto p = slash == std::string::npos ? std::nullopt : toNumber<long>(item.substr(0, slash));
    const auto q = slash == std::string::npos ? std::nullopt : toNumber<int>(item.substr(slash + 1));
    if (!p || !q) throw std::invalid_argument("--convergents: '" + io::shortText(item) + "' is not p/q (two whole numbers)");
    list.emplace_back(*p, *q);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return list;
}

void printText(const CantorusFlux& r, double seconds) {
  std::printf("# MacKay-Meiss-Percival flux |W(minimax) - W(minimizing)| of the Birkhoff p/q orbits about (-sqrt K, 0)\n");
  std::printf("# %-9s %13s %13s  %-36s %s\n", "p/q", "R(minimizing)", "R(minimax)", "flux per step", "scan");
  for (std::size_t i = 0; i < r.terms.size(); ++i) {
    const MmpActionDifference& t = r.terms[i];
    const std::string pq = std::to_string(t.p) + "/" + std::to_string(t.q);
    std::printf("  %-9s %13.6Lg %13.6Lg  %-36s %s\n", pq.c_str(), t.minimizing.orbit.residue, t.minimax.orbit.residue,
                quadText(t.flux, 30).c_str(), r.narrowed[i] ? "narrow" : "annulus");
  }
  if (r.limit)
    std::printf("# limit: %.15Lg +- %.2Lg (the last term; tail bound |d| r/(1 - r), r = %.3Lg)\n", r.limit->value,
                r.limit->uncertainty, r.limit->ratio);
  else
    std::printf("# limit: none (%s)\n", r.limitProblem.c_str());
  std::printf("# seconds: %.3f\n", seconds);
}

int runCantorus(CantorusOptions o) {
  CantorusRequest& r = o.request;
  r.K = o.map.K;
  r.convergents = parseConvergents(o.convergents);
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  io::checkCommandFiles({{"--out", o.out, io::FileUse::Output}});
  const auto started = std::chrono::steady_clock::now();
  CantorusFlux result;
  try {
    result = cantorusFlux(r, interruptToken());  // Ctrl-C: the program's one stop, within a scan's chunk
  } catch (const OperationStopped&) {
    std::fprintf(stderr, "interrupted: no cantorus flux (nothing written)\n");
    return 130;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string json = cantorusFluxJson(r, result, seconds) + "\n";
  if (!o.out.empty()) io::writeFileAtomically(o.out, json);
  if (o.json) std::fputs(json.c_str(), stdout);
  else printText(result, seconds);
  return 0;
}
}  // namespace

void addCantorusCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<CantorusOptions>();
  CLI::App* cmd = app.add_subcommand(
      "cantorus", "the MacKay-Meiss-Percival flux through a cantorus about the central island: the action difference "
                  "of the minimax and minimizing Birkhoff orbits over its convergents p/q, and the limit "
                  "(docs/markov-tree.md)");
  addNumberOption(*cmd, "--K", o->map.K, "map parameter K of Q: y′ = y + 2(x² − K), x′ = x + y′ (§2); in (0, 1]");
  cmd->add_option("--convergents", o->convergents, "p/q,p/q,…: the cantorus's convergents, in order")->required();
  addNumberOption(*cmd, "--inner", o->request.innerRadius, "the annulus scanned: inner distance from (-sqrt K, 0) along the symmetry lines");
  addNumberOption(*cmd, "--outer", o->request.outerRadius, "the annulus scanned: outer distance");
  addNumberOption(*cmd, "--spacing", o->request.spacing, "the scan's sample spacing along the lines");
  addNumberOption(*cmd, "--narrow-width", o->request.narrowHalfWidth,
                  "half-width of the windows about the previous convergent's points, where the annulus finds no pair");
  addNumberOption(*cmd, "--narrow-spacing", o->request.narrowSpacing, "the sample spacing in those windows");
  cmd->add_flag("--json", o->json, "print JSON instead of the table");
  cmd->add_option("--out", o->out, "also write the JSON here (atomically)");
  cmd->callback([o, &status] { status = runCantorus(*o); });
}

}  // namespace archipelago::cli
