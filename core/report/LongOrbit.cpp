#include "core/report/LongOrbit.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/paper/PaperTable.hpp"
#include "core/view/ViewExport.hpp"

namespace archipelago::report {

bool isChain138(const IslandChain& chain) noexcept {
  return chain.period == paper::kChain138Period ||
         std::find(chain.hierarchy.begin(), chain.hierarchy.end(), paper::kChain138Period) != chain.hierarchy.end();
}

namespace {

/// Rank `rank` identified (nothing when it is too short to identify).
std::optional<LongOrbitView> viewOf(const TrappingState& run, std::size_t rank, const std::string& runFile) {
  const SegmentRecord& record = run.longest.items().at(rank);
  LongOrbitView v;
  v.rank = rank;
  v.record = record;
  v.steps = record.length * run.params.q;
  try {
    auto chain = identifySegmentChain(run.params, record);
    if (!chain) return std::nullopt;
    v.chain = std::move(*chain);
  } catch (const std::invalid_argument&) {
    return std::nullopt;  // too short to identify
  }
  v.command = "archipelago-cli replay " + runFile + " --segment " + std::to_string(rank) + " --identify --out segment" +
              std::to_string(rank) + ".csv";
  return v;
}

void draw(const TrappingState& run, LongOrbitView& v, std::uint64_t maxPoints) {
  auto trace = traceSegment(run.params, v.record, maxPoints);
  if (trace) v.points = std::move(trace->points);
  // At least 2^16 grid units, as the GUI's zoom to a segment (PortraitController::zoomToRegion).
  v.view = framedInBox(v.chain.island, run.params.map, 1.0, run.params.map.width() * 0x1p-36L);
}

}  // namespace

LongOrbitFigures longOrbitFigures(const TrappingState& run, std::size_t candidates, std::uint64_t maxPoints,
                                  const std::string& runFile) {
  if (maxPoints < 3) throw std::invalid_argument("longOrbitFigures: maxPoints must be at least 3");
  LongOrbitFigures f;
  const std::size_t kept = run.longest.items().size();
  for (std::size_t rank = 0; rank < std::min(candidates, kept); ++rank) {
    ++f.examined;
    auto v = viewOf(run, rank, runFile);
    if (!v) continue;
    const bool on138 = isChain138(v->chain.chain);
    if (!f.longest || on138) draw(run, *v, maxPoints);  // the others are only identified
    if (!f.longest) f.longest = *v;
    if (on138) {
      f.chain138 = std::move(*v);
      break;
    }
  }
  return f;
}

Provenance longOrbitProvenance(const TrappingState& run, const LongOrbitView& v) {
  Provenance p = mapProvenance(run.params.map);
  addView(p, PhysicalRect{v.view.x0, v.view.x1, v.view.y0, v.view.y1});
  p.add("Image", "segment replayed, its states as dots");
  p.add("Orbit", std::to_string(v.record.orbit));
  p.add("Steps", std::to_string(v.steps));
  p.add("Command", v.command);
  return p;
}

}  // namespace archipelago::report
