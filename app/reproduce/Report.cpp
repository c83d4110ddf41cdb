#include "Report.hpp"

#include <QString>
#include <QStringList>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <optional>
#include <set>
#include <stop_token>
#include <vector>

#include "core/atlas/AtlasExport.hpp"
#include "core/atlas/AtlasJob.hpp"
#include "core/export/StatisticsCsv.hpp"
#include "core/markovtree/MarkovTreeExport.hpp"
#include "core/tail/BruteForceSurvival.hpp"
#include "core/tail/TailResult.hpp"
#include "core/tail/TailScan.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"
#include "core/paper/PaperTable.hpp"
#include "core/portrait/PortraitColours.hpp"
#include "core/portrait/PortraitExport.hpp"
#include "core/report/FigureRequests.hpp"
#include "core/report/LongOrbit.hpp"
#include "core/report/ReportPlan.hpp"
#include "core/report/ReportWriters.hpp"
#include "core/report/RunStatements.hpp"
#include "core/report/TheoryStatements.hpp"
#include "core/runfile/CheckpointedRun.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/scan/ScanBox.hpp"
#include "core/stats/ReferenceSlopes.hpp"
#include "core/stats/RunEnsemble.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/stats/StatisticsTable.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/theory/TheoryCurves.hpp"
#include "ui/report/ReportFigures.hpp"

namespace archipelago::app {

namespace fs = std::filesystem;
using report::ReportFigure;
using report::ReportItem;
using report::ReportRun;
using report::ReportSize;

namespace {

/// Set by SIGINT/SIGTERM: the run or scan in progress is saved at its next chunk and the report stops; the same
/// command resumes it.
volatile std::sig_atomic_t gInterrupted = 0;
extern "C" void onInterrupt(int) { gInterrupted = 1; }

/// Between the stages that keep no state of their own (figures, timings): stop at once when interrupted.
void stopIfInterrupted() {
  if (gInterrupted) {
    std::fprintf(stderr, "interrupted: every finished run is saved\n");
    throw Interrupted{};
  }
}

/// Runs, resumes or reuses one run file under OUTDIR/runs (core's runOrResumeFile: locked, checkpointed every
/// minute and at an interrupt).
TrappingState runOrReuse(const ReportRun& r, const fs::path& runs, int threads) {
  const fs::path file = runs / r.file;
  CheckpointedRunOptions options;
  options.run.threads = threads;
  options.checkpointSeconds = 60;
  options.stopRequested = [] { return gInterrupted != 0; };
  options.warning = [](const std::string& reason, double retry) {
    std::fprintf(stderr, "WARNING: checkpoint not written: %s; the run goes on and retries in %g s\n", reason.c_str(),
                 retry);
  };
  auto lastLine = std::chrono::steady_clock::now();
  RunFileOutcome outcome;
  try {
    outcome = runOrResumeFile(file, r.params, options, [&](const TrappingState&, const TrappingProgress& pr) {
      const auto now = std::chrono::steady_clock::now();
      if (now - lastLine > std::chrono::seconds(60)) {
        lastLine = now;
        std::fprintf(stderr, "%s: %.1f %%, ETA %.0f s\n", file.filename().c_str(), 100 * pr.fraction, pr.etaSeconds);
      }
    });
  } catch (const std::exception& e) {  // the report's own run: recomputing it is the remedy
    throw std::runtime_error(std::string(e.what()) + " (a run of the report: remove " + file.string() +
                             " to compute it again)");
  }
  if (outcome.reused) std::fprintf(stderr, "reusing %s\n", file.c_str());
  else if (outcome.resumed) std::fprintf(stderr, "resumed %s\n", file.c_str());
  if (!outcome.state.finished()) {
    std::fprintf(stderr, "interrupted: %s saved at %.1f %%\n", file.c_str(),
                 100.0 * static_cast<double>(outcome.state.blocksDone) / static_cast<double>(outcome.state.params.T));
    throw Interrupted{};
  }
  return outcome.state;
}

/// Runs (or resumes, or reuses) the report's K scan (core's runKScan: one run file per K).
std::vector<ScanRunSummary> scanOrReuse(KScanRequest r, int threads) {
  r.base.threads = threads;
  std::stop_source stop;
  auto last = std::chrono::steady_clock::now();
  KScanObserver observer;
  observer.progress = [&](const KScanProgress& p) {
    if (gInterrupted) stop.request_stop();
    const auto now = std::chrono::steady_clock::now();
    if (now - last > std::chrono::seconds(60)) {
      last = now;
      std::fprintf(stderr, "%s\n",
                   io::formatC("K scan: K = %g (%zu of %zu), %.1f %%, ETA %.0f s", p.K, p.index + 1, p.count,
                               100 * p.fractionScan(), p.etaScan).c_str());
    }
  };
  observer.warning = [](const std::string& w) { std::fprintf(stderr, "WARNING: %s\n", w.c_str()); };
  const KScanOutcome outcome = runKScan(r, observer, stop.get_token());
  if (!outcome.finished) {
    std::fprintf(stderr, "interrupted: the K scan is saved in %s\n", outcome.stoppedFile.c_str());
    throw Interrupted{};
  }
  return outcome.runs;
}

/// Runs (or resumes, or reuses) the report's tail scan (core's runTailScan in one process: a tail file per K).
TailScanSummary tailScanOrReuse(TailScanRequest r, int threads) {
  r.base.threads = threads;
  r.warning = [](const std::string& w) { std::fprintf(stderr, "WARNING: %s\n", w.c_str()); };
  std::stop_source stop;
  auto last = std::chrono::steady_clock::now();
  TailScanView view;
  view.progress = [&](std::size_t, double K, const TailState&, const TailProgress& p) {
    if (gInterrupted) stop.request_stop();
    const auto now = std::chrono::steady_clock::now();
    if (now - last > std::chrono::seconds(60)) {
      last = now;
      std::fprintf(stderr, "tail scan: K = %s, level %zu of %zu\n", scanKText(K).c_str(), p.level, p.levels);
    }
  };
  view.checkpointWarning = [](const std::string& reason, double retry) {
    std::fprintf(stderr, "WARNING: checkpoint not written: %s; the sampler goes on and retries in %g s\n",
                 reason.c_str(), retry);
  };
  OneProcess process;
  const TailScanOutcome outcome = runTailScan(r, view, process, stop.get_token());
  if (outcome.end != TailScanOutcome::End::finished) {
    std::fprintf(stderr, "interrupted: the tail scan is saved in %s\n", outcome.checkpoint.c_str());
    throw Interrupted{};
  }
  return outcome.summary;
}

std::vector<QPointF> qPoints(const std::vector<PhysicalPoint>& points) {
  std::vector<QPointF> out;
  out.reserve(points.size());
  for (const auto& p : points) out.emplace_back(static_cast<double>(p.x), static_cast<double>(p.y));
  return out;
}

/// Throws the figure writer's error.
void check(bool ok, const QString& error) {
  if (!ok) throw std::runtime_error(error.toStdString());
}

/// The report in progress: its folder, its items and figures.
class Report {
 public:
  explicit Report(const ReportOptions& o) : o_(o), full_(o.size == ReportSize::full), drawing_(o.only.empty()) {}

  int run() {
    const auto started = std::chrono::steady_clock::now();
    const std::set<report::Need> needs =
        drawing_ ? report::allNeeds() : std::set<report::Need>{report::needOf(o_.only)};
    // What each part needs computed first (b₂·D needs the K = 0.1 run).
    if (needs.count(report::Need::theory) || drawing_) theory();
    stopIfInterrupted();
    if (needs.count(report::Need::smallK)) smallK();
    stopIfInterrupted();
    // The Markov tree's item needs the run (α), the run box's b₂ and the tail sampler, all made by k01.
    const bool atlas = needs.count(report::Need::atlas) > 0;
    if (needs.count(report::Need::k01) || needs.count(report::Need::b2) || atlas)
      k01(needs.count(report::Need::b2) > 0 || atlas, atlas);
    stopIfInterrupted();
    if (needs.count(report::Need::scan)) scan();
    stopIfInterrupted();
    if (needs.count(report::Need::tailScan)) tailScan();
    if (needs.count(report::Need::timing))
      for (auto& it : report::timingStatements(report::measureStepTiming(o_.threads))) items_.push_back(std::move(it));
    stopIfInterrupted();
    if (drawing_) markovFigure();
    // The items in the order of the paper's table.
    std::vector<ReportItem> ordered;
    for (const paper::Statement& s : paper::statements())
      for (const ReportItem& it : items_)
        if (it.statement == &s) ordered.push_back(it);
    if (!drawing_) return printOnly(ordered);

    stopIfInterrupted();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    io::writeFileAtomically(o_.out / "items.csv", report::itemsCsv(ordered));
    report::ReportPage page{report::sizeName(o_.size), seconds, ordered, figures_};
    const std::string html = report::indexHtml(page);
    io::writeFileAtomically(o_.out / "index.html", html);
    QStringList images;
    for (const ReportFigure& f : figures_) images << QString::fromStdString("figures/" + f.file + ".png");
    QString error;
    check(ui::report::writePdf(QString::fromStdString(html), QString::fromStdString(o_.out.string()), images,
                               QString::fromStdString((o_.out / "report.pdf").string()), &error),
          error);
    const auto differs = std::count_if(ordered.begin(), ordered.end(),
                                       [](const ReportItem& it) { return it.mark == report::Mark::differs; });
    std::printf("report: %s (%s; %.0f s)\n", (o_.out / "index.html").c_str(),
                report::markSummary(ordered, full_).c_str(), seconds);
    return differs == 0 ? 0 : 2;
  }

 private:
  int printOnly(const std::vector<ReportItem>& ordered) {
    for (const ReportItem& it : ordered)
      if (it.id() == o_.only) {
        const paper::Statement& s = *it.statement;
        std::printf("%s (%s): %s\npaper: %s\nours: %s\n%stolerance: %s (%s)\nmark: %s\nnote: %s\ncommand: %s\n",
                    std::string(s.id).c_str(), std::string(s.section).c_str(), std::string(s.words).c_str(),
                    std::string(s.paperText).c_str(), report::numberText(it.ours, it.error).c_str(),
                    it.reference ? ("compared with: " + report::numberText(it.reference) + "\n").c_str() : "",
                    io::shortestText(it.toleranceUsed()).c_str(), std::string(s.toleranceWhy).c_str(),
                    report::markText(it.mark), it.note.c_str(), it.command.c_str());
        return it.mark == report::Mark::differs ? 2 : 0;
      }
    throw std::runtime_error("--only '" + o_.only + "': the statement was not computed");
  }

  fs::path figure(const std::string& stem) const { return o_.out / "figures" / stem; }
  QString base(const std::string& stem) const { return QString::fromStdString(figure(stem).string()); }

  void statisticFigure(Statistic s, const TrappingState& run, const TrappingStatistics& st, const std::string& stem,
                       const std::string& number, const std::string& caption) {
    if (!drawing_) return;
    QString error;
    check(ui::report::writeStatisticFigure(s, run, st, theoryCurves(run.params, st), base(stem), &error), error);
    figures_.push_back({number, caption, stem});
  }

  void portraitFigure(const PortraitRequest& r, const QString& title, const std::string& stem, const std::string& number,
                      const std::string& caption, const ui::report::FigureMarkers& markers = {}) {
    const PortraitResult portrait = renderPortrait(r);
    const PhysicalRect v = r.view.physical(r.map);
    QString error;
    check(ui::report::writePortraitFigure(colourize(portrait.raster, ColourMapName::Inferno), double(v.x0),
                                          double(v.x1), double(v.y0), double(v.y1), title, base(stem),
                                          portraitProvenance(r), &error, markers),
          error);
    figures_.push_back({number, caption, stem});
  }

  // §2, §4 (closed forms), §7 (the 138-chain), appendix C; figs. 1, 2, 4, 5.
  void theory() {
    for (auto& it : report::theoryStatements()) items_.push_back(std::move(it));
    if (!drawing_) return;
    portraitFigure(report::figureOneRequest(o_.size), QStringLiteral("Fig. 1 — the islands of Q at K = 0.1"), "fig1", "1",
                   "the islands at K = 0.1 (orbits from a grid of seeds; <code>" +
                       report::html(report::figureOneCommand(o_.size)) + "</code>)");
    stopIfInterrupted();
    orbit138_ = report::chain138Orbit();
    if (orbit138_) {
      member138_.name = QStringLiteral("members of the elliptic period-138 orbit (periodic-orbit finder)");
      for (const auto& z : orbit138_->points) member138_.points.emplace_back(double(z.x), double(z.y));
    }
    for (const bool enlargement : {false, true}) {
      const std::string stem = enlargement ? "fig2b" : "fig2a";
      portraitFigure(report::figureTwoRequest(o_.size, enlargement),
                     enlargement ? QStringLiteral("Fig. 2b — the sea near the 138-chain's member")
                                 : QStringLiteral("Fig. 2a — the chaotic sea of Q* at K = 0.1"),
                     stem, enlargement ? "2b" : "2a",
                     std::string(enlargement ? "the enlargement around x + √K = 0.352, y = 0.034, where the paper sees a "
                                               "member of the 138 = 6 × 23 chain (circled: the elliptic period-138 "
                                               "orbit's members found there)"
                                             : "orbits of the chaotic sea (visits of 256 long orbits; black: islands, "
                                               "and the spurious islands of the accelerator modes)") +
                         " (<code>" + report::html(report::figureTwoCommand(o_.size, enlargement)) + "</code>)",
                     enlargement ? member138_ : ui::report::FigureMarkers{});
      stopIfInterrupted();
    }
    // Fig. 4: the paper's two panels, the level curves of eq. (ham), K = 0, and of eq. (hamb), K > 0.
    std::vector<double> levels;
    for (int k = -12; k <= 12; ++k) levels.push_back(0.5 * k);
    const paper::Figure& four = paper::figure(4);
    for (std::size_t i = 0; i < four.panels.size(); ++i) {
      const int sign = static_cast<int>(i);  // a: s = 0, b: s = +1
      const std::string number = paper::panelName(four, four.panels[i]), stem = "fig" + number;
      QString error;
      check(ui::report::writeLevelCurveFigure(
                [sign](double X, double Y) { return report::smallKHamiltonian(X, Y, sign); }, -3, 3, -4, 4, levels,
                QStringLiteral("Fig. %1 — level curves, H = 0, ±0.5, …").arg(QString::fromStdString(number)),
                base(stem), report::levelCurveProvenance(sign, {-3, 3, -4, 4}), &error),
            error);
      figures_.push_back({number, report::html(std::string(four.panels[i].content)), stem});
    }
    QString error;
    check(ui::report::writeTrappingTimeFigures(
              base("fig5"), report::figureProvenance("small-K theory for K < 0: T(X0) and F(T)"), &error),
          error);
    const paper::Figure& five = paper::figure(5);
    for (const paper::FigurePanel& p : five.panels)
      figures_.push_back({paper::panelName(five, p), report::html(std::string(p.content)), "fig" + paper::panelName(five, p)});
  }

  // §4: fig. 3's three runs and the decay runs.
  void smallK() {
    const fs::path runs = o_.out / "runs";
    const TrappingState a = runOrReuse(report::smallKRun('a', o_.size), runs, o_.threads);
    const TrappingState b = runOrReuse(report::smallKRun('b', o_.size), runs, o_.threads);
    const TrappingState c = runOrReuse(report::smallKRun('c', o_.size), runs, o_.threads);
    const TrappingState d3 = runOrReuse(report::decayRun(1e-3, o_.size), runs, o_.threads);
    const TrappingState d2 = runOrReuse(report::decayRun(1e-2, o_.size), runs, o_.threads);
    for (auto& it : report::smallKStatements(a, b, c, d3, d2, o_.size)) items_.push_back(std::move(it));
    const paper::Figure& three = paper::figure(3);
    const TrappingState* runsOf[] = {&a, &b, &c};
    for (std::size_t i = 0; i < three.panels.size(); ++i) {
      const TrappingState& r = *runsOf[i];
      statisticFigure(Statistic::f, r, statisticsOf(r), "fig" + paper::panelName(three, three.panels[i]),
                      paper::panelName(three, three.panels[i]),
                      io::formatC("f<sub>t</sub> at K = %g with the small-K theory (%.3g steps)", r.params.map.K,
                                  r.stepsDone()));
    }
  }

  // §5, §7: the K = 0.1 run with its q = 1 companion; figs. 6, 7, 8; b₂; the tail.
  void k01(bool withB2, bool withAtlas) {
    const fs::path runs = o_.out / "runs";
    const ReportRun made = report::k01Run(o_.size);
    const TrappingState run = runOrReuse(made, runs, o_.threads);
    const TrappingState companion = runOrReuse(report::k01CompanionRun(o_.size), runs, o_.threads);
    TrappingStatistics st;
    try {
      st = splicedStatisticsOf(run, companion);
    } catch (const std::invalid_argument& e) {  // no crossover: the run's own statistics, said so
      std::fprintf(stderr, "WARNING: %s; the K = 0.1 statistics are the run's own\n", e.what());
      st = statisticsOf(run);
    }
    const TailAnalysis tail = analyseTail(ensembleOf({run}));
    for (auto& it : report::k01Statements(run, st, tail, full_, made.command)) items_.push_back(std::move(it));
    for (auto& it : report::tailStatements(tail, full_)) items_.push_back(std::move(it));
    // Issue #29: P_t beyond brute force by splitting on segment age, checked against this run where both have data.
    // The sampler keeps no file here: an interrupted one starts again (a second at the quick size).
    const TailRequest sampler = report::tailSamplerRequest(o_.size);
    TailRunOptions samplerOptions;
    samplerOptions.threads = o_.threads;
    std::stop_source stopSampler;
    const TailState sampled = runTail(
        startTail(sampler), samplerOptions,
        [&](const TailState&, const TailProgress&) {
          if (gInterrupted) stopSampler.request_stop();
        },
        stopSampler.get_token());
    stopIfInterrupted();
    const TailResult samplerResult = tailResult(sampled);
    items_.push_back(report::tailSplittingStatement(compareWithRuns(sampled, samplerResult, {run}),
                                                    report::tailSamplerCommand(o_.size)));
    double runBoxB2 = 0;
    if (withB2) {
      const MapParameters paperBox = report::paperSizedBox();
      const StochasticAreaResult inPaperBox = computeStochasticArea(report::stochasticAreaRequest(o_.size, paperBox));
      const StochasticAreaResult inRunBox = computeStochasticArea(report::stochasticAreaRequest(o_.size, run.params.map));
      runBoxB2 = stochasticAreaOf(run.params.map, inRunBox.fraction()).area;  // b₂: the area
      const std::string command = report::cliCommand(io::formatC(
          "stochastic-area --xmin=%g --xmax %g --iterations %llu", paperBox.xmin, paperBox.xmax,
          static_cast<unsigned long long>(report::stochasticAreaRequest(o_.size, paperBox).iterations)));
      for (auto& it : report::stochasticAreaStatements(inPaperBox, paperBox, inRunBox, run, st, tail, full_, command))
        items_.push_back(std::move(it));
    }
    if (withAtlas) markovTree(run, sampled, runBoxB2);
    if (!drawing_) return;
    const std::string steps = io::formatC(" at K = 0.1 (%.3g steps; below %.3g steps the q = 1 companion's)",
                                          run.stepsDone() + companion.stepsDone(), st.splicedAt);
    for (const int number : {6, 7}) {
      const paper::Figure& f = paper::figure(number);
      for (const paper::FigurePanel& p : f.panels) {
        const auto s = statisticWithKey(p.statisticKey);
        if (!s) continue;
        statisticFigure(*s, run, st, "fig" + paper::panelName(f, p), paper::panelName(f, p),
                        std::string(statisticInfo(*s).symbolRich) + steps);
      }
    }
    longOrbitFigures(run, made.file);
    stopIfInterrupted();
    tailFigure(run, tail);
    {
      QString error;
      double factor = 1;
      const Series levels = reliableSurvivalIn(samplerResult, run, st, &factor);
      check(ui::report::writeStatisticFigure(
                Statistic::P, run, st, theoryCurves(run.params, st), levels,
                QStringLiteral("P_t by splitting (tail, %1 × %2), reliable levels × %3")
                    .arg(sampler.population)
                    .arg(sampler.replicas)
                    .arg(factor, 0, 'g', 3),
                base("tail-splitting"), &error),
            error);
      figures_.push_back({"tail", io::formatC("P<sub>t</sub> at K = 0.1: the run's, spliced with its q = 1 companion "
                                              "(line), and the tail sampler's (diamonds: %zu reliable levels to t = %.3g "
                                              "steps, %.3g steps of the sampler; its P<sub>t</sub> counts the segments of "
                                              "blocks of q steps, here times α₁/α<sub>q</sub> = %.3g to count the q = 1 "
                                              "process's, as the line does; <code>%s</code>)",
                                              levels.x.size(), largestReliableT(samplerResult), samplerResult.steps,
                                              factor, report::html(report::tailSamplerCommand(o_.size)).c_str()),
                          "tail-splitting"});
    }
  }

  // Fig. 8: the longest segment replayed and zoomed, its chain identified; the longest on the 138-chain.
  void longOrbitFigures(const TrappingState& run, const std::string& runName) {
    const report::LongOrbitFigures lo = report::longOrbitFigures(run, full_ ? 30 : 10, 1'000'000, runName);
    const auto chainText = [](const IslandChain& c) {
      std::string h;
      for (const int level : c.hierarchy) h += (h.empty() ? "" : " → ") + std::to_string(level);
      return io::formatC("period %d (hierarchy %s), member at (%.5Lf, %.5Lf)", c.period, h.c_str(), c.member.x,
                         c.member.y);
    };
    const auto draw = [&](const report::LongOrbitView& v, const std::string& number, const std::string& what) {
      ui::report::FigureMarkers centre;
      if (v.chain.chain.centre) {
        centre.name = QStringLiteral("the chain's elliptic periodic orbit");
        for (const auto& z : v.chain.chain.centre->points) centre.points.emplace_back(double(z.x), double(z.y));
      }
      const std::string title = io::formatC("Fig. %s — segment %zu: %.3g steps, chain of period %d", number.c_str(),
                                            v.rank, double(v.steps), v.chain.chain.period);
      QString error;
      check(ui::report::writePointsFigure(qPoints(v.points), double(v.view.x0), double(v.view.x1), double(v.view.y0),
                                          double(v.view.y1), QString::fromUtf8(title.c_str()), base("fig" + number),
                                          report::longOrbitProvenance(run, v), &error, centre),
            error);
      figures_.push_back({number,
                          what + " segment " + std::to_string(v.rank) + " of the K = 0.1 run (" +
                              io::formatC("%.3g", double(v.steps)) + " steps, orbit " + std::to_string(v.record.orbit) +
                              "), replayed exactly and zoomed to one island of its chain: " +
                              report::html(chainText(v.chain.chain)) + " (<code>" + report::html(v.command) + "</code>)",
                          "fig" + number});
    };
    if (lo.longest) draw(*lo.longest, "8a", "the longest identifiable");
    if (lo.chain138 && lo.chain138->rank != (lo.longest ? lo.longest->rank : SIZE_MAX)) {
      draw(*lo.chain138, "8b", "on the 138 = 6 × 23 chain (§7): the longest such,");
    } else if (!lo.chain138 && orbit138_) {
      portraitFigure(report::chain138NeighbourhoodRequest(o_.size),
                     QStringLiteral("Fig. 8b — orbits near the 138-chain's member"), "fig8b", "8b",
                     "none of the run's " + std::to_string(lo.examined) + " longest segments sticks to the 138-chain "
                     "(a run of the paper's size is needed: its longest, ~6·10⁷ steps, did); instead, orbits from a "
                     "grid of seeds near the chain's member, its elliptic orbit circled",
                     member138_);
    }
  }

  // Not in the paper: the running exponent γ(t) of P_t against the later literature's asymptotic exponents.
  void tailFigure(const TrappingState& run, const TailAnalysis& tail) {
    ui::report::FigureCurve windows;
    windows.name = QStringLiteral("γ(t) over log-spaced windows (95 % bootstrap intervals)");
    windows.symbols = true;
    for (const TailWindow& w : tail.windows) {
      windows.x.push_back(std::sqrt(w.from * w.to));
      windows.y.push_back(w.gammaP);
      windows.error.push_back((w.gammaPInterval.hi - w.gammaPInterval.lo) / 2);
    }
    std::vector<ui::report::FigureCurve> curves{windows};
    double from = 1e300, to = 0;  // the reference lines span the windows
    for (const TailWindow& w : tail.windows) from = std::min(from, w.from), to = std::max(to, w.to);
    for (const ReferenceExponent& r : referenceExponents()) {
      ui::report::FigureCurve c;
      c.x = {from, to};
      c.y = {r.gamma, r.gamma};
      c.name = QStringLiteral("%1: asymptotic (literature: %2)").arg(r.gamma).arg(QString::fromUtf8(r.source));
      c.dashed = true;
      curves.push_back(std::move(c));
    }
    QString error;
    check(ui::report::writeCurvesFigure(curves, {QStringLiteral("P_t ~ t^−γ: the running exponent γ(t) at K = 0.1"),
                                                 QStringLiteral("t (steps)"), QStringLiteral("γ"), true, false},
                                        base("tail-gamma"), runProvenance(run), &error),
          error);
    figures_.push_back({"T", "the running exponent γ(t) of P<sub>t</sub> ~ t<sup>−γ</sup> over log-spaced windows (the "
                             "last ends where 10 segments remain beyond it), beside the later literature's asymptotic "
                             "exponents, which no finite window decides between: the paper's open question (§7)",
                        "tail-gamma"});
  }

  // §5's K scan (the paper's 26 K; not drawn by the paper).
  void scan() {
    const std::vector<ScanRunSummary> runs =
        scanOrReuse(report::kScanRequest(o_.size, o_.out / "runs" / (std::string("kscan-") + report::sizeName(o_.size))),
                    o_.threads);
    items_.push_back(report::kScanStatement(runs, full_, report::kScanCommand(o_.size)));
    if (!drawing_) return;
    QString error;
    check(ui::report::writeScanFigures(
              runs, base("kscan"), report::figureProvenance("K scan of §5", report::kScanCommand(o_.size)), &error),
          error);
    const std::string command =
        " (<code>" + report::html(report::kScanCommand(o_.size)) + "</code>; the GUI's Tools ▸ K Scan…)";
    figures_.push_back({"S1", "the K scan of §5: f<sub>t</sub> for the 26 K, each in its own box" + command, "kscan-ft"});
    figures_.push_back({"S2", "the local exponent −d log C<sub>τ</sub>/d log τ over K and τ (grey: no data)",
                        "kscan-heatmap"});
    figures_.push_back({"S3", "D(K) with its honest error (a bootstrap over segments; no bar where the longest "
                              "segments dominate D)", "kscan-d"});
    figures_.push_back({"S4", "the longest segment and the fraction of the steps in segments ≥ 10<sup>4</sup> against "
                              "K: the slow algebraic decay of §5 shows as segments beyond 10<sup>4</sup> steps",
                        "kscan-long"});
  }

  // §7 (later work, issue 55): the tail sampler over K (its files in runs/, reused or resumed), its exponent over
  // 10⁴–10⁶ averaged over K.
  void tailScan() {
    const TailScanSummary summary = tailScanOrReuse(
        report::tailScanRequest(o_.size, o_.out / "runs" / (std::string("tailscan-") + report::sizeName(o_.size))),
        o_.threads);
    items_.push_back(report::tailGammaKStatement(summary.K, report::tailGammaKExponents(summary), full_,
                                                 report::tailScanCommand(o_.size)));
  }

  // §7 (later work, issue 40): the atlas of the run's map (kept in runs/, resumed when stopped), its Markov tree and
  // the tree's P_t against the tail sampler's levels.
  void markovTree(const TrappingState& run, const TailState& sampled, double b2) {
    const AtlasRequest request = report::k01AtlasRequest(o_.size);
    const fs::path file = o_.out / "runs" / report::k01AtlasFile(o_.size);
    std::stop_source stop;
    auto last = std::chrono::steady_clock::now();
    const AtlasProgress progress = [&](const Atlas& sofar, int done, const std::string& stage) {
      if (gInterrupted) stop.request_stop();
      const auto now = std::chrono::steady_clock::now();
      if (now - last > std::chrono::seconds(60)) {
        last = now;
        std::fprintf(stderr, "atlas: %d of %zu islands known done: %s\n", done, sofar.nodes.size(), stage.c_str());
      }
    };
    // Core's reuse-or-resume of the file (core/atlas/AtlasJob.hpp), written at the end.
    const AtlasFileOutcome outcome = atlasOrResumeFile(file, request, progress, stop.get_token());
    if (!outcome.discarded.empty())
      std::fprintf(stderr, "WARNING: %s; the atlas was computed again\n", outcome.discarded.c_str());
    if (outcome.reused) std::fprintf(stderr, "reusing %s\n", file.c_str());
    if (outcome.atlas.cancelled) {
      std::fprintf(stderr, "interrupted: the atlas is saved in %s\n", file.c_str());
      throw Interrupted{};
    }
    const Atlas& atlas = outcome.atlas;
    const double alpha = statisticsOf(run).alpha;
    const std::string command = report::markovTreeCommand(o_.size, alpha, b2);
    MarkovTreeRequest mr;
    mr.alpha = alpha;
    mr.b2 = b2;
    mr.tMax = static_cast<double>(sampled.request.maxSteps);
    mr.atlasSource = file.filename().string();
    mr.tailSource = "the report's tail sampler";
    MarkovTreeResult tree;
    try {
      tree = computeMarkovTree(atlas, mr, &sampled);
    } catch (const std::invalid_argument& e) {
      items_.push_back(report::makeItem("markov-tree", std::nullopt, 0, full_, command,
                                        std::string("no tree from the atlas: ") + e.what()));
      return;
    }
    items_.push_back(report::markovTreeStatement(*tree.comparison, tree.tree, atlas.request.depth, alpha, b2, command));
    if (!drawing_) return;
    const Series model = markovTreeCurve(tree);
    // The model's exponential end is drawn down to a thousandth of the smallest level, not to 10⁻³⁰⁸ (the axis
    // would hold nothing else).
    double floor = 1;
    for (const MarkovTreeLevelComparison& m : tree.comparison->levels) floor = std::min(floor, 1e-3 * m.measured);
    ui::report::FigureCurve line;
    for (std::size_t i = 0; i < model.x.size(); ++i)
      if (model.value[i] >= floor) {
        line.x.push_back(model.x[i]);
        line.y.push_back(model.value[i]);
      }
    line.name = QStringLiteral("Markov tree of the atlas (depth %1), P_t = w S(t)").arg(atlas.request.depth);
    ui::report::FigureCurve levels;
    levels.symbols = true;
    levels.name = QStringLiteral("tail sampler (reliable levels)");
    for (const MarkovTreeLevelComparison& m : tree.comparison->levels) {
      levels.x.push_back(m.t);
      levels.y.push_back(m.measured);
      levels.error.push_back(m.measuredError);
    }
    QString error;
    check(ui::report::writeCurvesFigure({line, levels},
                                        {QStringLiteral("P_t at K = 0.1: the Markov tree of the atlas against the tail"),
                                         QStringLiteral("t (steps)"), QStringLiteral("P_t"), true, true},
                                        base("markov-tree"), markovTreeProvenance(tree), &error),
          error);
    figures_.push_back({"M", io::formatC("the Meiss–Ott Markov tree built from the atlas of depth %d (no fitted "
                                         "parameter) against the tail sampler's P<sub>t</sub> (docs/markov-tree.md)",
                                         atlas.request.depth) +
                                 " (<code>" + report::html(command) + "</code>)",
                        "markov-tree"});
  }

  // Appendix C, not drawn by the paper: the Markov model's ε(τ).
  void markovFigure() {
    const auto c = report::markovEpsilon();
    ui::report::FigureCurve eps;
    eps.x = c.tau;
    eps.y = c.epsilon;
    QString error;
    check(ui::report::writeCurvesFigure({eps}, {QStringLiteral("Markov model (appendix C): ε(τ), m = 20, N = 1000"),
                                                QStringLiteral("τ"), QStringLiteral("ε(τ)")},
                                        base("markov-epsilon"),
                                        report::figureProvenance("Markov model of appendix C: epsilon(tau)", c.command),
                                        &error),
          error);
    figures_.push_back({"C", "the Markov model's ε(τ) = (C(τ) − C<sub>is</sub>(τ))/C<sub>is</sub>(0) for one segment of "
                             "m = 20 among N = 1000 (<code>" + report::html(c.command) + "</code>)",
                        "markov-epsilon"});
  }

  const ReportOptions& o_;
  const bool full_;
  const bool drawing_;
  std::vector<ReportItem> items_;
  std::vector<ReportFigure> figures_;
  std::optional<PeriodicOrbit> orbit138_;
  ui::report::FigureMarkers member138_;
};

}  // namespace

void installReportInterruptHandlers() {
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
}

int runReport(const ReportOptions& options) {
  const fs::path& out = options.out;
  // OUTDIR may be new, but its parent must exist (a typo must not create a tree of folders), as for a scan.
  const fs::path parent = fs::absolute(out).parent_path();
  if (!fs::exists(out) && !fs::is_directory(parent))
    throw std::invalid_argument("OUTDIR " + out.string() + ": its folder " + parent.string() + " does not exist");
  if (fs::exists(out) && !fs::is_directory(out)) throw std::invalid_argument("OUTDIR " + out.string() + " is not a folder");
  fs::create_directories(out);
  const io::FileLock lock = io::FileLock::acquire(out / "index.html");  // one report per folder at a time
  fs::create_directories(out / "figures");
  fs::create_directories(out / "runs");
  // What a killed report left half-written (only temporaries: every output is published atomically).
  io::removeStaleTemporariesIn(out);
  io::removeStaleTemporariesIn(out / "figures");
  return Report(options).run();
}

}  // namespace archipelago::app
