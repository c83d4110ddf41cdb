#include "core/export/StatisticsCsv.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <system_error>

#include "core/io/AtomicFile.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/runspec/RunSpecJson.hpp"

namespace archipelago {

namespace {

/// 17 significant digits, shortest form of %g, never the locale's decimal separator.
std::string number(double v) {
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 17);
  return std::string(buffer, r.ptr);
}

std::string number(std::uint64_t v) { return std::to_string(v); }
std::string number(std::int64_t v) { return std::to_string(v); }

/// A CSV field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
std::string field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (const char c : s) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

void line(std::string& out, std::string_view name, const std::string& value) { csvMetadataLine(out, name, value); }

std::string text(std::string_view s) { return std::string(s); }

void writeFile(const std::filesystem::path& path, const std::string& content) { io::writeFileAtomically(path, content); }

bool hasTheory(const std::vector<TheoryCurve>& theory, Statistic s) {
  for (const TheoryCurve& c : theory)
    if (c.statistic == s) return true;
  return false;
}

}  // namespace

Provenance runProvenance(const TrappingState& state) {
  const MapCoefficients& c = state.coefficients;
  Provenance p;
  p.add("program", programDescription());
  // The parameters as the run-spec codec writes them (runspec/RunSpec.hpp): same keys, same digits.
  const nlohmann::json parameters = spec::parametersJson(state.params);
  for (const ParameterRule& rule : parameterRules())
    p.add(std::string(rule.key), parameters.at(std::string(rule.key)).dump());
  p.add("blocks_done", number(state.blocksDone));
  p.add("orbits", number(state.orbitBegin) + " to " + number(state.orbitEnd) + " (exclusive)");
  p.add("A", number(std::int64_t{c.A}));
  p.add("B", number(std::int64_t{c.B}));
  p.add("C", number(std::int64_t{c.C}));
  p.add("m", std::to_string(c.m));
  p.add("kernel", state.kernel.empty() ? std::string("unknown") : state.kernel);
  return p;
}

std::string runParametersLine(const TrappingState& state) {
  const nlohmann::json parameters = spec::parametersJson(state.params);
  std::string out;
  for (const char* key : {"K", "xmin", "xmax", "Xr", "q", "T", "M", "seed"})
    out += (out.empty() ? "" : ", ") + std::string(key) + " = " + parameters.at(key).dump();
  return out + "; " + number(state.blocksDone) + " of " + number(state.params.T) + " blocks";
}

std::string csvMetadataHeader(const TrappingState& state) {
  std::string out;
  for (const auto& [key, value] : runProvenance(state).fields) line(out, key, value);
  return out;
}

std::string csvNumber(double v) { return number(v); }

void csvMetadataLine(std::string& out, std::string_view name, const std::string& value) {
  out += "# ";
  out += name;
  out += ": ";
  out += value;
  out += '\n';
}

bool hasBlocksAffectedColumn(const TrappingStatistics& statistics) noexcept { return statistics.blockAffectedBelow > 0; }

std::string blocksAffectedColumnNote(const TrappingStatistics& statistics) {
  if (!hasBlocksAffectedColumn(statistics)) return {};
  return "; blocks_affected (1: t below 10 q = " + number(statistics.blockAffectedBelow) +
         " steps, the statistics of blocks of q steps, not of the q = 1 process)";
}

std::string blocksAffectedCell(const TrappingStatistics& statistics, double t) {
  if (!hasBlocksAffectedColumn(statistics)) return {};
  return t < statistics.blockAffectedBelow ? ",1" : ",0";
}

std::string statisticCsvFileName(Statistic s) { return text(statisticInfo(s).fileStem) + ".csv"; }
std::string theoryCsvFileName(Statistic s) { return text(statisticInfo(s).fileStem) + ".theory.csv"; }

std::string statisticCsv(const TrappingState& state, const TrappingStatistics& statistics, Statistic s) {
  const StatisticInfo& info = statisticInfo(s);
  const Series& series = seriesOf(statistics, s);
  std::string out = csvMetadataHeader(state);
  line(out, "statistic", text(info.key) + ": " + text(info.description) +
                             (figurePanelsOf(info.statistic).empty() ? std::string()
                                                       : " (Karney 1983, fig. " + figurePanelsOf(info.statistic) + ")"));
  // Issue #26: below 10 q a run of q > 1 describes blocks of q steps, not the paper's q = 1 process; the rows are
  // marked (blocks_affected = 1) unless the statistics were spliced with a q = 1 companion.
  const bool marked = hasBlocksAffectedColumn(statistics);
  line(out, "columns", text(info.abscissaLabel) + "; " + text(info.valueLabel) + "; " + text(info.key) + "_error" +
                           blocksAffectedColumnNote(statistics));
  line(out, "error", text(info.error));
  if (statistics.splicedAt > 0)
    line(out, "spliced", "below t = " + number(statistics.splicedAt) +
                             " steps f_t is the q = 1 companion's, above it the run's; every other statistic is "
                             "derived from that spliced f_t");
  out += text(info.abscissa) + ',' + text(info.key) + ',' + text(info.key) + "_error" + (marked ? ",blocks_affected" : "") + "\n";
  for (std::size_t i = 0; i < series.x.size(); ++i) {
    out += number(series.x[i]) + ',' + number(series.value[i]) + ',' + number(series.error[i]);
    out += blocksAffectedCell(statistics, series.x[i]);
    out += '\n';
  }
  return out;
}

std::string theoryCsv(const TrappingState& state, const std::vector<TheoryCurve>& theory, Statistic s) {
  if (!hasTheory(theory, s)) return {};
  const StatisticInfo& info = statisticInfo(s);
  std::string out = csvMetadataHeader(state);
  line(out, "theory", "small-K theory of Karney 1983, section 4, over " + text(info.key));
  for (const TheoryCurve& c : theory) {
    if (c.statistic != s) continue;
    if (c.kind == TheoryCurve::Kind::verticalLine) {
      line(out, "vertical_line", c.label + "; " + text(info.abscissa) + " = " + number(c.at));
    } else {
      line(out, "curve", c.label + "; amplitude " + number(c.amplitude) + " fitted over " + number(c.fitFrom) +
                             " <= " + text(info.abscissa) + " <= " + number(c.fitTo) + " (" +
                             std::to_string(c.fitPoints) + " points, rms log residual " + number(c.rmsLogResidual) +
                             ")");
    }
  }
  out += "curve," + text(info.abscissa) + ',' + text(info.key) + '\n';
  for (const TheoryCurve& c : theory) {
    if (c.statistic != s || c.kind != TheoryCurve::Kind::series) continue;
    const std::string name = field(c.label);
    for (std::size_t i = 0; i < c.curve.x.size(); ++i)
      out += name + ',' + number(c.curve.x[i]) + ',' + number(c.curve.value[i]) + '\n';
  }
  return out;
}

std::string summaryCsv(const TrappingState& state, const TrappingStatistics& statistics, const RunSummary& summary) {
  // Every value and error is the run summary's (core/stats/RunSummary.hpp), which `stats`, Python and the GUI print:
  // D's error is the one they give (none when the longest segments dominate D), never the subsets' standard error,
  // which stands in a row of its own under its own name (issue 51: summary.csv once gave D = 1088 ± 487 where
  // `stats` said D has no error).
  const RunSummary& r = summary;
  const auto optional = [](double v) { return std::isfinite(v) ? number(v) : std::string(); };
  std::string out = csvMetadataHeader(state);
  line(out, "summary", "alpha: mean segment length (steps); D: diffusion coefficient (section 3); "
                       "D_error_subsets: the standard error of D over the subsets of orbits, for reference only (the "
                       "heavy tail makes it far too small, section 5); gamma_P: the tail's exponent, P_t ~ t^-gamma "
                       "(gamma_P_low, gamma_P_high: its interval); sum_t_f_t: C_0 (close to 1); segments: recorded; "
                       "longest_blocks: longest length the highest non-empty bin can hold (blocks of q steps)");
  line(out, "error", "one sigma; empty: none can be given (see D_error and gamma_P below); 0: exact");
  line(out, "D_error", r.DErrorNote);
  if (r.judged) {
    line(out, "gamma_P", r.gammaPText);
    line(out, "verdict", r.tailVerdict);
  }
  out += "quantity,value,error\n";
  out += "alpha," + number(r.alpha) + ',' + number(r.alphaError) + '\n';
  out += "D," + number(r.D) + ',' + optional(r.DError) + '\n';
  out += "D_error_subsets," + number(r.DSubsetsError) + ",\n";
  out += "gamma_P," + optional(r.gammaP) + ",\n";
  out += "gamma_P_low," + optional(r.gammaPInterval.lo) + ",\n";
  out += "gamma_P_high," + optional(r.gammaPInterval.hi) + ",\n";
  out += "sum_t_f_t," + number(r.sumTf) + ",0\n";
  out += "segments," + number(r.segments) + ",0\n";
  out += "longest_blocks," + number(statistics.longestBlocks) + ",0\n";
  return out;
}

std::string longestSegmentsCsv(const TrappingState& state) {
  std::string out = csvMetadataHeader(state);
  line(out, "table", "longest trapped segments, longest first (Karney 1983, section 6)");
  line(out, "columns", "rank; length in steps (q blocks); length in blocks; orbit; first block; random draws "
                       "before it; start state X, Y (units of 2^-52); start point x, y");
  out += "rank,length_steps,length_blocks,orbit,start_block,start_draws,start_X,start_Y,start_x,start_y\n";
  const FixedPointMap map(state.params.map);
  std::uint64_t rank = 0;
  for (const SegmentRecord& r : state.longest.items()) {
    const PhysicalPoint start = map.toPhysical(r.start.z);
    out += number(++rank) + ',' + number(r.length * state.params.q) + ',' + number(r.length) + ',' + number(r.orbit) +
           ',' + number(r.start.block) + ',' + number(r.start.draws) + ',' + number(r.start.z.X) + ',' +
           number(r.start.z.Y) + ',' + number(static_cast<double>(start.x)) + ',' +
           number(static_cast<double>(start.y)) + '\n';
  }
  return out;
}

std::vector<CsvFile> statisticsCsvFiles(const TrappingState& state, const TrappingStatistics& statistics,
                                        const std::vector<TheoryCurve>& theory, const RunSummary& summary) {
  std::vector<CsvFile> files;
  for (const StatisticInfo& info : statisticsTable()) {
    files.push_back({statisticCsvFileName(info.statistic), statisticCsv(state, statistics, info.statistic)});
    if (hasTheory(theory, info.statistic))
      files.push_back({theoryCsvFileName(info.statistic), theoryCsv(state, theory, info.statistic)});
  }
  files.push_back({summaryCsvFileName, summaryCsv(state, statistics, summary)});
  files.push_back({longestSegmentsCsvFileName, longestSegmentsCsv(state)});
  return files;
}

std::vector<std::filesystem::path> writeStatisticsCsv(const std::filesystem::path& dir, const TrappingState& state,
                                                      const TrappingStatistics& statistics,
                                                      const std::vector<TheoryCurve>& theory,
                                                      const RunSummary& summary) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create folder " + dir.string() + ": " + ec.message());
  std::vector<std::filesystem::path> written;
  for (const CsvFile& f : statisticsCsvFiles(state, statistics, theory, summary)) {
    writeFile(dir / f.name, f.text);
    written.push_back(dir / f.name);
  }
  return written;
}

std::vector<std::filesystem::path> writeStatisticCsv(const std::filesystem::path& path, const TrappingState& state,
                                                     const TrappingStatistics& statistics,
                                                     const std::vector<TheoryCurve>& theory, Statistic s) {
  std::vector<std::filesystem::path> written;
  writeFile(path, statisticCsv(state, statistics, s));
  written.push_back(path);
  if (hasTheory(theory, s)) {
    std::filesystem::path theoryPath = path;
    if (theoryPath.extension() == ".csv") theoryPath.replace_extension(".theory.csv");
    else theoryPath += ".theory.csv";
    writeFile(theoryPath, theoryCsv(state, theory, s));
    written.push_back(theoryPath);
  }
  return written;
}

}  // namespace archipelago
