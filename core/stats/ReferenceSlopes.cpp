#include "core/stats/ReferenceSlopes.hpp"

#include <cmath>

#include "core/io/NumberText.hpp"
#include "core/paper/PaperTable.hpp"

namespace archipelago {

const std::vector<ReferenceExponent>& referenceExponents() {
  static const std::vector<ReferenceExponent> table = {
      {paper::kGammaCristadoroKetzmerick, "Cristadoro & Ketzmerick 2008"},
      {paper::kGammaVenegeroles, "Venegeroles 2009"},
      {paper::kGammaShepelyansky, "Shepelyansky 2010"},
      {paper::kGammaChirikovShepelyansky, "Chirikov & Shepelyansky 1999"},
  };
  return table;
}

std::vector<ReferenceSlope> referenceSlopes(const Series& P) {
  double minimum = 0;
  for (std::size_t i = 0; i < P.x.size(); ++i)
    if (P.value[i] > 0 && P.x[i] > 0 && (minimum == 0 || P.value[i] < minimum)) minimum = P.value[i];
  if (!(minimum > 0)) return {};
  double anchor = 0, anchorP = 0, last = 0;
  for (std::size_t i = 0; i < P.x.size(); ++i) {
    if (!(P.x[i] > 0)) continue;
    last = std::max(last, P.x[i]);
    if (P.value[i] >= 100 * minimum) {
      anchor = P.x[i];
      anchorP = P.value[i];
    }
  }
  if (!(anchor > 0)) return {};
  const double from = anchor / 10, to = std::max(last, 10 * anchor);
  constexpr int kSamples = 40;
  std::vector<ReferenceSlope> out;
  for (const ReferenceExponent& r : referenceExponents()) {
    ReferenceSlope slope;
    slope.gamma = r.gamma;
    const std::string g = io::formatC("%g", r.gamma);
    slope.label = "t^-" + g + " (" + r.source + ")";
    std::string source = r.source;
    if (const auto amp = source.find('&'); amp != std::string::npos) source.replace(amp, 1, "&amp;");
    slope.labelRich = "t<sup>\u2212" + g + "</sup> (" + source + ")";
    for (int k = 0; k < kSamples; ++k) {
      const double t = from * std::pow(to / from, static_cast<double>(k) / (kSamples - 1));
      slope.line.x.push_back(t);
      slope.line.value.push_back(anchorP * std::pow(t / anchor, -r.gamma));
      slope.line.error.push_back(0);
    }
    out.push_back(std::move(slope));
  }
  return out;
}

}  // namespace archipelago
