// archipelago-reproduce: Karney (1983) reproduced by one command.  Thin: options, the runs (core's
// runTrapping with run files under OUTDIR, so --full resumes and reuses them), core's list of statements
// (core/report), the GUI's plot code for the figures (ui/report), then index.html, items.csv and report.pdf.
#include <CLI/CLI.hpp>
#include <QApplication>
#include <QDir>
#include <QString>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "core/io/AtomicFile.hpp"
#include "core/portrait/ColourMap.hpp"
#include "core/report/PaperItems.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/theory/TheoryCurves.hpp"
#include "ui/report/ReportFigures.hpp"

namespace fs = std::filesystem;
using namespace archipelago;

namespace {

/// Runs (or resumes, or reuses) one run file under OUTDIR/runs, checkpointing every minute.
TrappingState runOrReuse(const TrappingParameters& p, const fs::path& file, int threads) {
  TrappingState state;
  if (fs::exists(file)) {
    state = loadRunFile(file);
    if (!(state.params == p)) throw std::runtime_error(file.string() + " holds a run of other parameters; remove it");
    if (state.finished()) {
      std::cerr << "reusing " << file.string() << "\n";
      return state;
    }
    std::cerr << "resuming " << file.string() << "\n";
  } else {
    state = startTrapping(p);
  }
  TrappingRunOptions options;
  options.threads = threads;
  auto last = std::chrono::steady_clock::now();
  state = runTrapping(std::move(state), options, [&](const TrappingState& s, const TrappingProgress& pr) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last > std::chrono::seconds(60)) {
      saveRunFile(file, s);
      last = now;
      std::fprintf(stderr, "%s: %.1f %%, ETA %.0f s\n", file.filename().c_str(), 100 * pr.fraction, pr.etaSeconds);
    }
  });
  saveRunFile(file, state);
  return state;
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
  char buf[64];
  if (error > 0) std::snprintf(buf, sizeof buf, "%.6g ± %.2g", *v, error);
  else std::snprintf(buf, sizeof buf, "%.8g", *v);
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
  std::string outdir;
  bool quick = false, full = false;
  int threads = 0;
  std::string only;
  app.add_option("OUTDIR", outdir, "the report folder (created; runs are kept in OUTDIR/runs and reused)")->required();
  auto* q = app.add_flag("--quick", quick, "CI size: a few minutes on two cores (the default)");
  app.add_flag("--full", full, "the paper's sizes (3.2·10¹² steps: days; resumable, reuses finished runs)")->excludes(q);
  app.add_option("--only", only, "compute and print this one statement (its id in items.csv), no figures");
  app.add_option("--threads", threads, "OpenMP threads (0: one per core)")->check(CLI::Range(0, 1024));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  QApplication qapp(argc, argv);
  try {
    const auto started = std::chrono::steady_clock::now();
    const fs::path out(outdir);
    fs::create_directories(out / "figures");
    fs::create_directories(out / "runs");
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
    // Fig. 3: f_t for small K with the theory of §4.
    const char* letters[] = {"a", "b", "c"};
    int i = 0;
    for (double K : {-1e-4, 0.0, 1e-4}) {
      const TrappingParameters p = report::smallKParameters(K, full);
      char name[64];
      std::snprintf(name, sizeof name, "smallk%s-%s.json", letters[i], size.c_str());
      const TrappingState run = runOrReuse(p, out / "runs" / name, threads);
      const TrappingStatistics st = statisticsOf(run);
      if (K < 0) items.push_back(report::negativeKCutoffItem(run));
      char caption[160];
      std::snprintf(caption, sizeof caption, "f<sub>t</sub> at K = %g with the small-K theory (%.3g steps)", K,
                    run.stepsDone());
      figure(Statistic::f, run, st, std::string("fig3") + letters[i], std::string("3") + letters[i], caption);
      ++i;
    }
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

    // Figs. 6 and 7: the K = 0.1 run.
    const TrappingState k01 = runOrReuse(report::k01Parameters(full), out / "runs" / ("k01-" + size + ".json"), threads);
    const TrappingStatistics st = statisticsOf(k01);
    for (auto& it : report::k01Items(k01, st, full)) items.push_back(std::move(it));
    for (auto& it : report::stochasticAreaItems(k01, st, full)) items.push_back(std::move(it));
    char steps[64];
    std::snprintf(steps, sizeof steps, " at K = 0.1 (%.3g steps)", k01.stepsDone());
    figure(Statistic::f, k01, st, "fig6a", "6a", std::string("f<sub>t</sub>") + steps);
    figure(Statistic::P, k01, st, "fig6b", "6b", std::string("P<sub>t</sub>") + steps);
    figure(Statistic::C, k01, st, "fig6c", "6c", std::string("C<sub>τ</sub>") + steps);
    figure(Statistic::localExponent, k01, st, "fig6d", "6d", std::string("−d log C/d log τ") + steps);
    figure(Statistic::S, k01, st, "fig7a", "7a", std::string("S<sub>t</sub>") + steps);
    figure(Statistic::Dt, k01, st, "fig7b", "7b", std::string("D<sub>t</sub> = S<sub>t</sub>/2t") + steps);
    // Appendix C, not drawn by the paper: the Markov model's ε(τ).
    if (drawing) {
      const auto c = report::markovEpsilon();
      if (!ui::report::writeCurveFigure(c.tau, c.epsilon, QStringLiteral("Markov model (appendix C): ε(τ), m = 20, N = 1000"),
                                        QStringLiteral("τ"), QStringLiteral("ε(τ)"),
                                        QString::fromStdString((out / "figures" / "markov-epsilon").string()), &error))
        throw std::runtime_error(error.toStdString());
      figures.push_back({"C", "the Markov model's ε(τ) = (C(τ) − C<sub>is</sub>(τ))/C<sub>is</sub>(0) for one segment of "
                              "m = 20 among N = 1000 (<code>" + html(c.command) + "</code>)", "markov-epsilon"});
    }
    for (auto& it : report::pendingItems()) items.push_back(std::move(it));
    if (!drawing) {
      if (auto rc = printOnly()) return *rc;
      throw std::invalid_argument("--only '" + only + "': no such statement (see the ids in items.csv)");
    }

    // items.csv, index.html, report.pdf.
    std::ostringstream csv;
    csv << "id,section,statement,paper_value,paper,ours,error,tolerance,mark,command,note\n";
    int differs = 0;
    for (const auto& it : items) {
      if (it.mark == report::Mark::differs) ++differs;
      csv << it.id << ',' << csvField(it.section) << ',' << csvField(it.statement) << ',' << csvField(it.paperValue)
          << ',' << (it.paper ? std::to_string(*it.paper) : "") << ',' << (it.ours ? number(it.ours) : "") << ','
          << it.error << ',' << it.tolerance << ',' << csvField(report::markText(it.mark)) << ','
          << csvField(it.command) << ',' << csvField(it.note) << '\n';
    }
    io::writeFileAtomically(out / "items.csv", csv.str());

    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
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
      << "<h2>Statements</h2>\n<table width=\"100%\"><tr><th width=\"8%\">id</th><th width=\"4%\">§</th>"
         "<th width=\"34%\">statement</th><th width=\"9%\">paper</th><th width=\"11%\">ours</th>"
         "<th width=\"5%\">tol.</th><th width=\"9%\">mark</th><th width=\"20%\">command</th></tr>\n";
    for (const auto& it : items) {
      const char* cls = it.mark == report::Mark::agrees ? "agrees"
                        : it.mark == report::Mark::differs ? "differs" : "other";
      char tol[32];
      std::snprintf(tol, sizeof tol, "%.2g", it.tolerance);
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
    h << "<h2>Not yet drawn</h2><p>Fig. 2 (orbits of the sea and the 138-chain "
         "enlargement), fig. 8 (the long orbit at the 138-chain), "
         "the K scan summary and the tail exponent against the literature are not yet "
         "in this report; <code>archipelago-cli portrait</code>, <code>replay --identify</code>, <code>scan</code> "
         "and <code>markov</code> produce their data.</p>\n</body></html>\n";
    io::writeFileAtomically(out / "index.html", h.str());
    if (!ui::report::writePdf(QString::fromStdString(h.str()), QString::fromStdString(out.string()), images,
                              QString::fromStdString((out / "report.pdf").string()), &error))
      throw std::runtime_error(error.toStdString());
    std::printf("report: %s (%zu statements, %d differ unexplained, %.0f s)\n", (out / "index.html").c_str(),
                items.size(), differs, seconds);
    return differs == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    return 1;
  }
}
