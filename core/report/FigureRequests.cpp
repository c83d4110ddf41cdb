#include "core/report/FigureRequests.hpp"

#include "core/io/NumberText.hpp"
#include "core/report/TheoryStatements.hpp"
#include "core/view/ViewExport.hpp"

namespace archipelago::report {

PortraitRequest figureOneRequest(ReportSize size) {
  PortraitRequest r;  // the default map: the paper's K = 0.1 box
  r.view = Viewport::fromPhysical(r.map, PhysicalRect{-0.8L, 0.5L, -0.65L, 0.65L});
  r.mode = PortraitMode::Orbits;
  r.width = r.height = size == ReportSize::full ? 1200 : 600;
  r.points = size == ReportSize::full ? 200'000'000 : 20'000'000;
  r.passes = 1;
  return r;
}

std::string figureOneCommand(ReportSize size) {
  return size == ReportSize::full ? cliCommand("portrait --view=-0.8,0.5,-0.65,0.65 --size 1200x1200 --mode orbits --points 200000000 --out fig1.png")
              : cliCommand("portrait --view=-0.8,0.5,-0.65,0.65 --size 600x600 --mode orbits --points 20000000 --out fig1.png");
}

PortraitRequest figureTwoRequest(ReportSize size, bool enlargement) {
  PortraitRequest r;  // the default map: the paper's K = 0.1 box
  r.mode = PortraitMode::Density;
  r.width = r.height = size == ReportSize::full ? 1200 : 600;
  if (enlargement) {
    constexpr long double h = 0.03L;  // half-width: the 138-chain member among the sea's other islands
    r.view = Viewport::fromPhysical(r.map, PhysicalRect{kChain138X - h, kChain138X + h, kChain138Y - h, kChain138Y + h});
    r.points = size == ReportSize::full ? 8'000'000'000ULL : 400'000'000ULL;
  } else {
    r.view = Viewport::fromPhysical(r.map, PhysicalRect{-0.8L, 0.5L, -0.65L, 0.65L});
    r.points = size == ReportSize::full ? 2'000'000'000ULL : 100'000'000ULL;
  }
  r.passes = 1;
  return r;
}

std::string figureTwoCommand(ReportSize size, bool enlargement) {
  const PortraitRequest r = figureTwoRequest(size, enlargement);
  const PhysicalRect v = r.view.physical(r.map);
  const std::string buf = io::formatC("portrait --view=%.4Lf,%.4Lf,%.4Lf,%.4Lf --size %dx%d --mode density --points %llu --out fig2%s.png",
                v.x0, v.x1, v.y0, v.y1, r.width, r.height, static_cast<unsigned long long>(r.points),
                                      enlargement ? "b" : "a");
  return cliCommand(buf);
}

PortraitRequest chain138NeighbourhoodRequest(ReportSize size) {
  PortraitRequest r;
  constexpr long double h = 0.004L;
  r.view = Viewport::fromPhysical(r.map, PhysicalRect{kChain138X - h, kChain138X + h, kChain138Y - h, kChain138Y + h});
  r.mode = PortraitMode::Orbits;
  r.width = r.height = 600;
  r.points = size == ReportSize::full ? 200'000'000 : 40'000'000;
  r.passes = 1;
  return r;
}

double smallKHamiltonian(double X, double Y, int sign) noexcept {
  return 0.5 * Y * Y - (2.0 / 3.0) * X * X * X + 2.0 * sign * X;
}

Provenance figureProvenance(const std::string& image, const std::string& command) {
  Provenance p = programProvenance();
  p.add("Image", image);
  if (!command.empty()) p.add("Command", command);
  return p;
}

Provenance levelCurveProvenance(int sign, const PhysicalRect& view) {
  Provenance p = figureProvenance(sign == 0 ? "level curves of H = Y^2/2 - 2X^3/3 (K = 0)"
                                            : "level curves of H = Y^2/2 - 2X^3/3 + 2X (K > 0)");
  addView(p, view);
  return p;
}

}  // namespace archipelago::report
