// archipelago-reproduce: Karney (1983) reproduced by one command.  Thin: options, the runs (core's
// runTrapping with run files under OUTDIR, so --full resumes and reuses them), core's list of statements
// (core/report), the GUI's plot code for the figures (ui/report), then index.html, items.csv and report.pdf.
#include <CLI/CLI.hpp>
#include <QApplication>

#include <clocale>
#include <QDir>
#include <QString>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <stop_token>

#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"
#include "core/portrait/ColourMap.hpp"
#include "core/report/LongOrbit.hpp"
#include "core/paper/PaperTable.hpp"
#include "core/report/PaperItems.hpp"
#include "core/spec/InputRules.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/runfile/CheckpointedRun.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/stats/RunEnsemble.hpp"
#include "core/stats/ReferenceSlopes.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/theory/TheoryCurves.hpp"
#include "ui/report/ReportFigures.hpp"

namespace fs = std::filesystem;
using namespace archipelago;

namespace {

/// Set by SIGINT/SIGTERM: the run or scan in progress is saved at its next chunk and the report stops; the same
/// command resumes it.
volatile std::sig_atomic_t gInterrupted = 0;
extern "C" void onInterrupt(int) { gInterrupted = 1; }

/// Thrown when interrupted, after the work in progress is saved.
struct Interrupted {};

/// Between the stages that keep no state of their own (figures, timings): stop at once when interrupted.
void stopIfInterrupted() {
  if (gInterrupted) {
    std::fprintf(stderr, "interrupted: every finished run is saved\n");
    throw Interrupted{};
  }
}

/// Runs (or resumes, or reuses) one run file under OUTDIR/runs, checkpointing every minute and at an interrupt.
TrappingState runOrReuse(const TrappingParameters& p, const fs::path& file, int threads) {
  const io::FileLock lock = io::FileLock::acquire(file);  // one report at a time per run file
  io::removeStaleTemporaries(file);
  TrappingState state;
  if (fs::exists(file)) {
    try {
      state = loadRunFile(file);
    } catch (const std::exception& e) {  // the report's own run: recomputing it is the remedy
      throw std::runtime_error(std::string(e.what()) + " (the report's run: remove " + file.string() +
                               " to compute it again)");
    }
    if (!(state.params == p)) throw std::runtime_error(file.string() + " holds a run of other parameters; remove it");
    if (state.finished()) {
      std::cerr << "reusing " << file.string() << "\n";
      return state;
    }
    std::cerr << "resuming " << file.string() << "\n";
  } else {
    state = startTrapping(p);
  }
  CheckpointedRunOptions options;  // core's loop of `archipelago-cli run` (runfile/CheckpointedRun.hpp)
  options.run.threads = threads;
  options.checkpoint = file;
  options.checkpointSeconds = 60;
  options.stopRequested = [] { return gInterrupted != 0; };
  options.warning = [](const std::string& reason, double retry) {
    std::fprintf(stderr, "WARNING: checkpoint not written: %s; the run goes on and retries in %g s\n", reason.c_str(),
                 retry);
  };
  LastCheckpoint last{state.blocksDone > 0 ? file.string() : std::string(), state.blocksDone};
  auto lastLine = std::chrono::steady_clock::now();
  state = runWithCheckpoints(std::move(state), options, last, [&](const TrappingState&, const TrappingProgress& pr) {
    const auto now = std::chrono::steady_clock::now();
    if (now - lastLine > std::chrono::seconds(60)) {
      lastLine = now;
      std::fprintf(stderr, "%s: %.1f %%, ETA %.0f s\n", file.filename().c_str(), 100 * pr.fraction, pr.etaSeconds);
    }
  });
  saveRunFileOrSayWhere(file, state, last);
  if (!state.finished()) {
    std::fprintf(stderr, "interrupted: %s saved at %.1f %%\n", file.c_str(),
                 100.0 * static_cast<double>(state.blocksDone) / static_cast<double>(state.params.T));
    throw Interrupted{};
  }
  return state;
}

/// Runs (or resumes, or reuses) the report's K scan in `dir` (core's runKScan: one run file per K).
std::vector<ScanRunSummary> scanOrReuse(const KScanRequest& request, int threads) {
  KScanRequest r = request;
  r.base.threads = threads;
  std::stop_source stop;
  auto last = std::chrono::steady_clock::now();
  KScanObserver observer;
  observer.progress = [&](const KScanProgress& p) {
    if (gInterrupted) stop.request_stop();
    const auto now = std::chrono::steady_clock::now();
    if (now - last > std::chrono::seconds(60)) {
      last = now;
      std::fprintf(stderr, "K scan: K = %g (%zu of %zu), %.1f %%, ETA %.0f s\n", p.K, p.index + 1, p.count,
                   100 * p.fractionScan(), p.etaScan);
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

std::vector<QPointF> qPoints(const std::vector<PhysicalPoint>& points) {
  std::vector<QPointF> out;
  out.reserve(points.size());
  for (const auto& p : points) out.emplace_back(static_cast<double>(p.x), static_cast<double>(p.y));
  return out;
}

std::string html(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

std::string number(const std::optional<double>& v, double error = 0) {
  if (!v) return "—";
  std::string buf;
  if (error > 0) buf = io::formatC("%.6g ± %.2g", *v, error);
  else buf = io::formatC("%.8g", *v);
  return buf;
}

std::string csvField(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

struct Figure {
  std::string number, caption, file;  // file stem under figures/
};

}  // namespace

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  CLI::App app{"Karney (1983) reproduced: every figure and number into OUTDIR/index.html and OUTDIR/report.pdf"};
  app.set_version_flag("--version", std::string("archipelago-reproduce ") + ARCHIPELAGO_VERSION);
  std::string outdir;
  bool quick = false, full = false;
  int threads = 0;
  std::string only;
  app.add_option("OUTDIR", outdir, "the report folder (created; runs are kept in OUTDIR/runs and reused)")->required();
  auto* q = app.add_flag("--quick", quick, "CI size: a few minutes on two cores (the default)");
  app.add_flag("--full", full, "the paper's sizes (3.2·10¹² steps: minutes on two cores; resumable, reuses finished runs)")->excludes(q);
  app.add_option("--only", only, "compute and print this one statement (its id in items.csv), no figures")
      ->check(CLI::Validator([](std::string& id) { return id.empty() ? std::string("an empty id") : std::string(); },
                             "ID"));
  app.add_option_function<std::string>(
         "--threads", [&threads](const std::string& text) { threads = readThreads(text); },
         "OpenMP threads (0: one per core; core's rule, at most " + std::to_string(kMaxThreads) + ")")
      ->type_name("INT");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // one ERROR line and status 2, as archipelago-cli (issue #23)
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {  // an option's own reader (--threads)
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    return 2;
  }
  // An unknown statement is refused before any work (issue #23: a typo once computed every run first).
  if (!only.empty() && paper::findStatement(only) == nullptr) {
    std::fprintf(stderr, "ERROR: --only '%s': no such statement (archipelago-reproduce --table lists them)\n",
                 only.c_str());
    return 2;
  }
  QApplication qapp(argc, argv);
  // Qt sets the user's locale for the C library; printf-style text of this program is never localised (a
  // decimal comma once split items.csv's columns and changed statement ids, issue #23).  Qt's own text uses
  // QLocale, which this does not touch.
  std::setlocale(LC_NUMERIC, "C");
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  try {
    const auto started = std::chrono::steady_clock::now();
    const fs::path out(outdir);
    // OUTDIR may be new, but its parent must exist (a typo must not create a tree of folders), as for a scan.
    const fs::path parent = fs::absolute(out).parent_path();
    if (!fs::exists(out) && !fs::is_directory(parent))
      throw std::invalid_argument("OUTDIR " + out.string() + ": its folder " + parent.string() + " does not exist");
    if (fs::exists(out) && !fs::is_directory(out))
      throw std::invalid_argument("OUTDIR " + out.string() + " is not a folder");
    fs::create_directories(out);
    const io::FileLock reportLock = io::FileLock::acquire(out / "index.html");  // one report per folder at a time
    fs::create_directories(out / "figures");
    fs::create_directories(out / "runs");
    // What a killed report left half-written (only temporaries: every output is published atomically).
    io::removeStaleTemporariesIn(out);
    io::removeStaleTemporariesIn(out / "figures");
    const std::string size = full ? "full" : "quick";

    std::vector<report::PaperItem> items = report::theoryItems();
    const bool drawing = only.empty();
    auto printOnly = [&]() -> std::optional<int> {
      for (const auto& it : items)
        if (it.id == only) {
          std::printf("%s (%s): %s\npaper: %s\nours: %s\ntolerance: %g\nmark: %s\nnote: %s\n", it.id.c_str(),
                      it.section.c_str(), it.statement.c_str(), it.paperValue.c_str(), number(it.ours, it.error).c_str(),
                      it.tolerance, report::markText(it.mark), it.note.c_str());
          return it.mark == report::Mark::differs ? 2 : 0;
        }
      return std::nullopt;
    };
    if (!drawing)
      if (auto rc = printOnly()) return *rc;
    std::vector<Figure> figures;
    QString error;
    auto figure = [&](Statistic s, const TrappingState& run, const TrappingStatistics& st, const std::string& stem,
                      const std::string& num, const std::string& caption) {
      if (!drawing) return;
      const QString base = QString::fromStdString((out / "figures" / stem).string());
      if (!ui::report::writeStatisticFigure(s, st, theoryCurves(run.params, st), base, &error))
        throw std::runtime_error(error.toStdString());
      figures.push_back({num, caption, stem});
    };

    // Fig. 1: the islands at K = 0.1 (core's portrait and colouring, drawn on the GUI's Qwt axes).
    if (drawing) {
      const PortraitRequest r = report::figureOneRequest(full);
      const PortraitResult portrait = renderPortrait(r);
      const PhysicalRect v = r.view.physical(r.map);
      if (!ui::report::writePortraitFigure(colourize(portrait.raster, ColourMapName::Inferno), double(v.x0),
                                           double(v.x1), double(v.y0), double(v.y1),
                                           QStringLiteral("Fig. 1 — the islands of Q at K = 0.1"),
                                           QString::fromStdString((out / "figures" / "fig1").string()), &error))
        throw std::runtime_error(error.toStdString());
      figures.push_back({"1", "the islands at K = 0.1 (orbits from a grid of seeds; <code>" +
                                  html(report::figureOneCommand(full)) + "</code>)", "fig1"});
    }
    stopIfInterrupted();
    // Fig. 2: the chaotic sea of Q* (dark), its holes the islands; (b) the enlargement with the 138-chain's member.
    const std::optional<PeriodicOrbit> orbit138 = drawing ? report::chain138Orbit() : std::nullopt;
    ui::report::FigureMarkers member138;
    if (orbit138) {
      member138.name = QStringLiteral("members of the elliptic period-138 orbit (periodic-orbit finder)");
      for (const auto& z : orbit138->points) member138.points.emplace_back(double(z.x), double(z.y));
    }
    for (bool enlargement : {false, true}) {
      if (!drawing) break;
      const PortraitRequest r = report::figureTwoRequest(full, enlargement);
      const PortraitResult portrait = renderPortrait(r);
      const PhysicalRect v = r.view.physical(r.map);
      const std::string stem = enlargement ? "fig2b" : "fig2a";
      if (!ui::report::writePortraitFigure(colourize(portrait.raster, ColourMapName::Inferno), double(v.x0),
                                           double(v.x1), double(v.y0), double(v.y1),
                                           enlargement ? QStringLiteral("Fig. 2b — the sea near the 138-chain's member")
                                                       : QStringLiteral("Fig. 2a — the chaotic sea of Q* at K = 0.1"),
                                           QString::fromStdString((out / "figures" / stem).string()), &error,
                                           enlargement ? member138 : ui::report::FigureMarkers{}))
        throw std::runtime_error(error.toStdString());
      figures.push_back({enlargement ? "2b" : "2a",
                         std::string(enlargement ? "the enlargement around x + √K = 0.352, y = 0.034, where the paper "
                                                   "sees a member of the 138 = 6 × 23 chain (circled: the elliptic "
                                                   "period-138 orbit's members found there)"
                                                 : "orbits of the chaotic sea (visits of 256 long orbits; black: "
                                                   "islands, and the spurious islands of the accelerator modes)") +
                             " (<code>" + html(report::figureTwoCommand(full, enlargement)) + "</code>)",
                         stem});
    }
    stopIfInterrupted();
    // Fig. 3: f_t for small K with the theory of §4.
    const char* letters[] = {"a", "b", "c"};
    int i = 0;
    for (double K : {-1e-4, 0.0, 1e-4}) {
      const TrappingParameters p = report::smallKParameters(K, full);
      const std::string name = io::formatC("smallk%s-%s.json", letters[i], size.c_str());
      const TrappingState run = runOrReuse(p, out / "runs" / name, threads);
      const TrappingStatistics st = statisticsOf(run);
      if (K < 0) items.push_back(report::negativeKCutoffItem(run));
      const std::string caption = io::formatC("f<sub>t</sub> at K = %g with the small-K theory (%.3g steps)", K,
                                              run.stepsDone());
      figure(Statistic::f, run, st, std::string("fig3") + letters[i], std::string("3") + letters[i], caption);
      ++i;
    }
    stopIfInterrupted();
    // Fig. 4: level curves of the three small-K Hamiltonians (eqs. hama, ham, hamb).
    if (drawing) {
      std::vector<double> levels;
      for (int k = -12; k <= 12; ++k) levels.push_back(0.5 * k);
      const char* names[] = {"a", "b", "c"};
      const char* words[] = {"K &lt; 0 (eq. hama: H = ½Y² − ⅔X³ − 2X)", "K = 0 (eq. ham: H = ½Y² − ⅔X³)",
                             "K &gt; 0 (eq. hamb: H = ½Y² − ⅔X³ + 2X)"};
      for (int s = -1; s <= 1; ++s) {
        const std::string stem = std::string("fig4") + names[s + 1];
        if (!ui::report::writeLevelCurveFigure(
                [s](double X, double Y) { return report::smallKHamiltonian(X, Y, s); }, -3, 3, -4, 4, levels,
                QStringLiteral("Fig. 4%1 — level curves, H = 0, ±0.5, …").arg(QLatin1String(names[s + 1])),
                QString::fromStdString((out / "figures" / stem).string()), &error))
          throw std::runtime_error(error.toStdString());
        figures.push_back({std::string("4") + names[s + 1], std::string("level curves for ") + words[s + 1], stem});
      }
    }
    // Fig. 5: T(X0) and F(T).
    if (drawing && !ui::report::writeTrappingTimeFigures(QString::fromStdString((out / "figures" / "fig5").string()), &error))
      throw std::runtime_error(error.toStdString());
    if (drawing) figures.push_back({"5a", "T(X<sub>0</sub>) for K &lt; 0 (eq. tneg)", "fig5a"});
    if (drawing) figures.push_back({"5b", "F(T) for K &lt; 0 with its two limits (eq. fneg)", "fig5b"});

    stopIfInterrupted();
    // Figs. 6 and 7: the K = 0.1 run.
    const TrappingState k01 = runOrReuse(report::k01Parameters(full), out / "runs" / ("k01-" + size + ".json"), threads);
    const TrappingStatistics st = statisticsOf(k01);
    const TailAnalysis tail = analyseTail(ensembleOf({k01}));
    for (auto& it : report::k01Items(k01, st, tail, full)) items.push_back(std::move(it));
    for (auto& it : report::localExponentRangeItems(k01, st, full)) items.push_back(std::move(it));
    for (auto& it : report::stochasticAreaItems(k01, st, tail, full)) items.push_back(std::move(it));
    for (auto& it : report::tailItems(tail, full)) items.push_back(std::move(it));
    std::string steps;
    steps = io::formatC(" at K = 0.1 (%.3g steps)", k01.stepsDone());
    figure(Statistic::f, k01, st, "fig6a", "6a", std::string("f<sub>t</sub>") + steps);
    figure(Statistic::P, k01, st, "fig6b", "6b", std::string("P<sub>t</sub>") + steps);
    figure(Statistic::C, k01, st, "fig6c", "6c", std::string("C<sub>τ</sub>") + steps);
    figure(Statistic::localExponent, k01, st, "fig6d", "6d", std::string("−d log C/d log τ") + steps);
    figure(Statistic::S, k01, st, "fig7a", "7a", std::string("S<sub>t</sub>") + steps);
    figure(Statistic::Dt, k01, st, "fig7b", "7b", std::string("D<sub>t</sub> = S<sub>t</sub>/2t") + steps);
    // Fig. 8: the longest segment replayed and zoomed, its chain identified; the longest on the 138-chain.
    if (drawing) {
      const std::string runName = "k01-" + size + ".json";
      const report::LongOrbitFigures lo = report::longOrbitFigures(k01, full ? 30 : 10, 1'000'000, runName);
      auto chainText = [](const IslandChain& c) {
        std::string h;
        for (int level : c.hierarchy) h += (h.empty() ? "" : " → ") + std::to_string(level);
        const std::string buf = io::formatC("period %d (hierarchy %s), member at (%.5Lf, %.5Lf)", c.period, h.c_str(),
                                            c.member.x, c.member.y);
        return std::string(buf);
      };
      auto drawSegment = [&](const report::LongOrbitView& v, const std::string& stem, const std::string& num,
                             const std::string& what) {
        ui::report::FigureMarkers centre;
        if (v.chain.chain.centre) {
          centre.name = QStringLiteral("the chain's elliptic periodic orbit");
          for (const auto& z : v.chain.chain.centre->points) centre.points.emplace_back(double(z.x), double(z.y));
        }
        const std::string title = io::formatC("Fig. %s — segment %zu: %.3g steps, chain of period %d", num.c_str(),
                                              v.rank, double(v.steps), v.chain.chain.period);
        if (!ui::report::writePointsFigure(qPoints(v.points), double(v.view.x0), double(v.view.x1), double(v.view.y0),
                                           double(v.view.y1), QString::fromUtf8(title.c_str()),
                                           QString::fromStdString((out / "figures" / stem).string()), &error, centre))
          throw std::runtime_error(error.toStdString());
        const std::string steps = io::formatC("%.3g", double(v.steps));
        figures.push_back({num, what + " segment " + std::to_string(v.rank) + " of the K = 0.1 run (" + steps +
                                    " steps, orbit " + std::to_string(v.record.orbit) + "), replayed exactly and "
                                    "zoomed to one island of its chain: " + html(chainText(v.chain.chain)) + " (<code>" +
                                    html(v.command) + "</code>)", stem});
      };
      if (lo.longest) drawSegment(*lo.longest, "fig8a", "8a", "the longest identifiable");
      if (lo.chain138 && lo.chain138->rank != (lo.longest ? lo.longest->rank : SIZE_MAX)) {
        drawSegment(*lo.chain138, "fig8b", "8b", "on the 138 = 6 × 23 chain (§7): the longest such,");
      } else if (!lo.chain138 && orbit138) {
        // No recorded segment sticks to the 138-chain: orbits near it (a grid of seeds around the member).
        PortraitRequest r;
        constexpr long double h = 0.004L;
        r.view = Viewport::fromPhysical(r.map, PhysicalRect{report::kChain138X - h, report::kChain138X + h,
                                                             report::kChain138Y - h, report::kChain138Y + h});
        r.mode = PortraitMode::Orbits;
        r.width = r.height = 600;
        r.points = full ? 200'000'000 : 40'000'000;
        r.passes = 1;
        const PortraitResult portrait = renderPortrait(r);
        const PhysicalRect v = r.view.physical(r.map);
        if (!ui::report::writePortraitFigure(colourize(portrait.raster, ColourMapName::Inferno), double(v.x0),
                                             double(v.x1), double(v.y0), double(v.y1),
                                             QStringLiteral("Fig. 8b — orbits near the 138-chain's member"),
                                             QString::fromStdString((out / "figures" / "fig8b").string()), &error,
                                             member138))
          throw std::runtime_error(error.toStdString());
        figures.push_back({"8b", "none of the run's " + std::to_string(lo.examined) + " longest segments sticks to the "
                                 "138-chain (a run of the paper's size is needed: its longest, ~6·10⁷ steps, did); "
                                 "instead, orbits from a grid of seeds near the chain's member, its elliptic orbit "
                                 "circled", "fig8b"});
      }
    }
    stopIfInterrupted();
    // §5's K scan (the paper's 26 K; not drawn by the paper).
    {
      const std::vector<ScanRunSummary> scan = scanOrReuse(report::kScanRequest(full, out / "runs" / ("kscan-" + size)), threads);
      items.push_back(report::kScanItem(scan, full));
      if (drawing) {
        if (!ui::report::writeScanFigures(scan, QString::fromStdString((out / "figures" / "kscan").string()), &error))
          throw std::runtime_error(error.toStdString());
        const std::string scanCmd = " (<code>" + html(report::kScanCommand(full)) + "</code>; the GUI's Tools ▸ K Scan…)";
        figures.push_back({"S1", "the K scan of §5: f<sub>t</sub> for the 26 K, each in its own box" + scanCmd, "kscan-ft"});
        figures.push_back({"S2", "the local exponent −d log C<sub>τ</sub>/d log τ over K and τ (grey: no data)",
                           "kscan-heatmap"});
        figures.push_back({"S3", "D(K) with its honest error (a bootstrap over segments; no bar where the longest "
                                 "segments dominate D)", "kscan-d"});
        figures.push_back({"S4", "the longest segment and the fraction of the steps in segments ≥ 10<sup>4</sup> "
                                 "against K: the slow algebraic decay of §5 shows as segments beyond 10<sup>4</sup> "
                                 "steps", "kscan-long"});
      }
    }
    // Appendix B: the Cray-1's 75 ns and 65 hours against this machine.
    for (auto& it : report::timingItems(report::measureStepTiming(threads))) items.push_back(std::move(it));
    stopIfInterrupted();
    // Not in the paper: the tail exponent against the later literature.
    if (drawing) {
      ui::report::FigureCurve windows;
      windows.name = QStringLiteral("γ over decades of t (95 % bootstrap intervals)");
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
        c.name = QStringLiteral("%1 (%2)").arg(r.gamma).arg(QString::fromUtf8(r.source));
        c.dashed = true;
        curves.push_back(std::move(c));
      }
      if (!ui::report::writeCurvesFigure(curves, {QStringLiteral("P_t ~ t^−γ: the local γ at K = 0.1 against the literature"),
                                                  QStringLiteral("t (steps)"), QStringLiteral("γ"), true, false},
                                         QString::fromStdString((out / "figures" / "tail-gamma").string()), &error))
        throw std::runtime_error(error.toStdString());
      figures.push_back({"T", "the tail exponent γ of P<sub>t</sub> ~ t<sup>−γ</sup> over decades of t (the last "
                              "ends where 10 segments remain beyond it) against the later literature's exponents: the "
                              "paper's open question (§7)", "tail-gamma"});
    }
    // Appendix C, not drawn by the paper: the Markov model's ε(τ).
    if (drawing) {
      const auto c = report::markovEpsilon();
      ui::report::FigureCurve eps;
      eps.x = c.tau;
      eps.y = c.epsilon;
      if (!ui::report::writeCurvesFigure({eps}, {QStringLiteral("Markov model (appendix C): ε(τ), m = 20, N = 1000"),
                                                 QStringLiteral("τ"), QStringLiteral("ε(τ)")},
                                         QString::fromStdString((out / "figures" / "markov-epsilon").string()), &error))
        throw std::runtime_error(error.toStdString());
      figures.push_back({"C", "the Markov model's ε(τ) = (C(τ) − C<sub>is</sub>(τ))/C<sub>is</sub>(0) for one segment of "
                              "m = 20 among N = 1000 (<code>" + html(c.command) + "</code>)", "markov-epsilon"});
    }
    if (!drawing) {
      if (auto rc = printOnly()) return *rc;
      throw std::invalid_argument("--only '" + only + "': no such statement (see the ids in items.csv)");
    }

    stopIfInterrupted();
    // items.csv, index.html, report.pdf.
    std::ostringstream csv;
    csv.imbue(std::locale::classic());  // never the user's decimal comma (issue #23)
    csv << "id,section,statement,paper_value,paper,ours,error,tolerance,mark,command,note\n";
    int differs = 0;
    for (const auto& it : items) {
      if (it.mark == report::Mark::differs) ++differs;
      csv << it.id << ',' << csvField(it.section) << ',' << csvField(it.statement) << ',' << csvField(it.paperValue)
          << ',' << (it.paper ? number(it.paper) : "") << ',' << (it.ours ? number(it.ours) : "") << ','
          << it.error << ',' << it.tolerance << ',' << csvField(report::markText(it.mark)) << ','
          << csvField(it.command) << ',' << csvField(it.note) << '\n';
    }
    io::writeFileAtomically(out / "items.csv", csv.str());

    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    auto markCount = [&](report::Mark m) {
      return std::count_if(items.begin(), items.end(), [m](const report::PaperItem& it) { return it.mark == m; });
    };
    std::ostringstream h;
    h << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Karney (1983) reproduced</title>"
         "<style>body{font-family:sans-serif;max-width:60em;margin:auto}table{border-collapse:collapse}"
         "td,th{border:1px solid #999;padding:2px 4px;font-size:small;vertical-align:top}"
         ".agrees{background:#dfd}.differs{background:#fdd}.other{background:#eee}</style></head><body>\n"
      << "<h1>Karney (1983), <i>Long-time correlations in the stochastic regime</i>, reproduced</h1>\n"
      << "<p>Generated by <code>archipelago-reproduce --" << size << "</code> (Archipelago " ARCHIPELAGO_VERSION
      << ") in " << std::lround(seconds) << " s. Each statement of the paper with its value, ours (± one sigma "
         "where there is an error), the tolerance, a mark and one command that reproduces it alone. "
         "Figures are numbered by first citation (README, \"Figures of the paper\") and drawn by the GUI's plot "
         "code; each links to its SVG. Differences: our map is 52-bit fixed point (the Cray's was 48-bit); D and "
         "the longest segment vary strongly from run to run (a heavy tail); b₂ depends on the box, b₂·D does not.</p>\n"
      << "<p><b>" << markCount(report::Mark::agrees) << " of " << items.size() << " statements agree</b>, "
      << markCount(report::Mark::differsExplained) << " differ for a stated reason, "
      << markCount(report::Mark::notAtThisSize) << " are not reproducible at this size"
      << (full ? "" : " (<code>--full</code> computes them)") << ", " << differs << " differ unexplained.</p>\n"
      << "<h2>Statements</h2>\n<table width=\"100%\"><tr><th width=\"8%\">id</th><th width=\"4%\">§</th>"
         "<th width=\"34%\">statement</th><th width=\"9%\">paper</th><th width=\"11%\">ours</th>"
         "<th width=\"5%\">tol.</th><th width=\"9%\">mark</th><th width=\"20%\">command</th></tr>\n";
    for (const auto& it : items) {
      const char* cls = it.mark == report::Mark::agrees ? "agrees"
                        : it.mark == report::Mark::differs ? "differs" : "other";
      const std::string tol = io::formatC("%.2g", it.tolerance);
      h << "<tr class=\"" << cls << "\"><td>" << it.id << "</td><td>" << html(it.section) << "</td><td>"
        << html(it.statement) << "<br><small>" << html(it.note) << "</small></td><td>" << html(it.paperValue)
        << "</td><td>" << number(it.ours, it.error) << "</td><td>" << (it.paper ? tol : "") << "</td><td>"
        << report::markText(it.mark) << "</td><td><code>" << html(it.command) << "</code></td></tr>\n";
    }
    h << "</table>\n<h2>Figures</h2>\n";
    QStringList images;
    for (const auto& f : figures) {
      h << "<p><b>Fig. " << f.number << "</b>: " << f.caption << " (<a href=\"figures/" << f.file
        << ".svg\">SVG</a>)<br><img src=\"figures/" << f.file << ".png\" width=\"600\"></p>\n";
      images << QString::fromStdString("figures/" + f.file + ".png");
    }
    h << "</body></html>\n";
    io::writeFileAtomically(out / "index.html", h.str());
    if (!ui::report::writePdf(QString::fromStdString(h.str()), QString::fromStdString(out.string()), images,
                              QString::fromStdString((out / "report.pdf").string()), &error))
      throw std::runtime_error(error.toStdString());
    std::printf("report: %s (%zu statements, %d differ unexplained, %.0f s)\n", (out / "index.html").c_str(),
                items.size(), differs, seconds);
    return differs == 0 ? 0 : 2;
  } catch (const Interrupted&) {
    std::fprintf(stderr, "the same command resumes the report from the saved runs\n");
    return 130;  // 128 + SIGINT, as a shell reports a process stopped by Ctrl-C
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    return 1;
  }
}
