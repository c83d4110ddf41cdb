#include "stats/RunStatistics.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace archipelago {

std::vector<std::uint64_t> orbitsPerSubset(const TrappingState& state) {
  const std::uint64_t n = state.params.subsets;
  std::vector<std::uint64_t> counts(n, 0);
  for (std::uint64_t i = state.orbitBegin; i < state.orbitEnd; ++i) counts[i % n] += 1;
  return counts;
}

TrappingStatistics statisticsOf(const TrappingState& state) {
  return computeStatistics(state.subsets, orbitsPerSubset(state), state.blocksDone, state.params.q);
}

std::string seriesCsv(const Series& s, const std::string& xName, const std::string& valueName) {
  std::ostringstream out;
  out.precision(17);
  out << xName << ',' << valueName << ",error\n";
  for (std::size_t i = 0; i < s.x.size(); ++i) out << s.x[i] << ',' << s.value[i] << ',' << s.error[i] << '\n';
  return out.str();
}

const std::vector<SeriesField>& statisticsSeriesFields() {
  static const std::vector<SeriesField> fields = {
      {"f", "t", "f_t", &TrappingStatistics::f},
      {"p", "t", "p_t", &TrappingStatistics::p},
      {"P", "t", "P_t", &TrappingStatistics::P},
      {"C", "tau", "C_tau", &TrappingStatistics::C},
      {"local_exponent", "tau", "minus_dlogC_dlogtau", &TrappingStatistics::localExponent},
      {"S", "t", "S_t", &TrappingStatistics::S},
      {"D_t", "t", "D_t", &TrappingStatistics::Dt},
  };
  return fields;
}

namespace {
void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}
}  // namespace

void writeStatisticsCsv(const std::filesystem::path& dir, const TrappingStatistics& stats) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create folder " + dir.string() + ": " + ec.message());
  for (const SeriesField& f : statisticsSeriesFields())
    writeFile(dir / (std::string(f.file) + ".csv"), seriesCsv(stats.*f.member, f.x, f.value));
  std::ostringstream s;
  s.precision(17);
  s << "quantity,value,error\n"
    << "alpha," << stats.alpha << ',' << stats.alphaError << '\n'
    << "D," << stats.D << ',' << stats.DError << '\n'
    << "sum_t_f_t," << stats.sumTf << ",0\n"
    << "segments," << stats.segments << ",0\n"
    << "longest_blocks," << stats.longestBlocks << ",0\n";
  writeFile(dir / "summary.csv", s.str());
}

}  // namespace archipelago
