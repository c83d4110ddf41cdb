#include "core/export/BoxInvariantCsv.hpp"

#include <cmath>
#include <numbers>

#include "core/export/StatisticsCsv.hpp"

namespace archipelago {

namespace {
/// As every CSV file writes numbers (csvNumber); empty for NaN (an undefined cell).
std::string number(double v) { return std::isnan(v) ? std::string() : csvNumber(v); }
void line(std::string& out, std::string_view name, const std::string& value) { csvMetadataLine(out, name, value); }
}  // namespace

std::string boxInvariantCsv(const TrappingState& state, const TrappingStatistics& statistics,
                            const StochasticAreaValue& b2, double DError) {
  const BoxInvariantQuantities q = boxInvariantQuantities(b2, statistics.D, DError);
  std::string out = csvMetadataHeader(state);
  line(out, "content", "b2 as an area (appendix A: b0 = L^2, b2 its stochastic part), the box-invariant b2*D "
                       "(eq. A3) and the application figures of sec. 6 (first-order accelerator modes of the "
                       "standard map); errors: D's one-sigma bootstrap error over segments, empty when the longest segments dominate D "
                       "(the subset error is far too small for this heavy tail), b2's own error not included");
  out += "quantity,value,error\n";
  const auto row = [&](const char* name, double value, double error) {
    out += std::string(name) + ',' + number(value) + ',' + number(error) + '\n';
  };
  row("b2_area", q.b2.area, 0);
  row("b2_fraction", q.b2.fraction, 0);
  row("box_area_L2", q.b2.boxArea, 0);
  row("D", statistics.D, DError);
  row("b2_D", q.b2D, q.b2DError);
  row("accelerator_factor_8_over_pi2_b2", q.acceleratorFactor, 0);
  row("enhancement_over_quasilinear_n1", q.enhancementN1, q.acceleratorFactor * DError / (std::numbers::pi * std::numbers::pi));
  return out;
}

std::string boxInvariantFtCsv(const TrappingState& state, const TrappingStatistics& statistics,
                              const StochasticAreaValue& b2) {
  std::string out = csvMetadataHeader(state);
  line(out, "statistic", "b2_f_t: b2 (an area, appendix A) times f_t; does not depend on the box for large t (eq. A3)");
  line(out, "b2", number(b2.area) + " (fraction " + number(b2.fraction) + " of L^2 = " + number(b2.boxArea) + ")");
  line(out, "columns", "t (steps); b2 f_t (area per step); b2_f_t_error (one sigma over the subsets)" +
                           blocksAffectedColumnNote(statistics));
  out += std::string("t,b2_f_t,b2_f_t_error") + (hasBlocksAffectedColumn(statistics) ? ",blocks_affected" : "") + "\n";
  const Series& f = statistics.f;
  for (std::size_t i = 0; i < f.x.size(); ++i)
    out += number(f.x[i]) + ',' + number(b2.area * f.value[i]) + ',' + number(b2.area * f.error[i]) +
           blocksAffectedCell(statistics, f.x[i]) + '\n';
  return out;
}

}  // namespace archipelago
