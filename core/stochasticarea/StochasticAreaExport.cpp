#include "core/stochasticarea/StochasticAreaExport.hpp"

#include <nlohmann/json.hpp>

#include "core/runspec/RunSpecJson.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"

namespace archipelago {

std::string stochasticAreaJson(const StochasticAreaRequest& r, const StochasticAreaResult& result) {
  using nlohmann::json;
  json curve = json::array();
  // b₂ is an area (appendix A), the box counting measures the fraction of the box: both, by their names.
  for (const auto& p : result.convergence)
    curve.push_back({{"iterations", p.iterations}, {"boxes_visited", p.boxesVisited},
                     {"b2_area", stochasticAreaOf(r.map, p.b2).area}, {"b2_fraction", p.b2}});
  json j;
  j["quantity"] = "b2: area of the chaotic sea of Q* in the box (Karney 1983, sec. 5 and appendix A: b0 = L^2), "
                  "b2_fraction: the fraction of the boxes of the grid it visits";
  j["map"] = spec::mapJson(r.map);
  j["Xr"] = r.Xr;
  j["q"] = r.q;
  j["orbits"] = r.orbits;
  j["seed"] = r.seed;
  j["grid"] = std::uint64_t{1} << r.gridBits;
  const StochasticAreaValue b2 = stochasticAreaOf(r.map, result.fraction());
  j["box_area"] = b2.boxArea;
  j["b2_area"] = b2.area;
  j["b2_fraction"] = b2.fraction;
  j["cancelled"] = result.cancelled;
  j["convergence"] = curve;
  return j.dump(2);
}

}  // namespace archipelago
