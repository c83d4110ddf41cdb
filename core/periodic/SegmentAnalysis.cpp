#include "core/periodic/SegmentAnalysis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <limits>
#include <utility>

#include "core/io/NumberText.hpp"
#include "core/run/TrappingRun.hpp"

#include "core/io/AtomicFile.hpp"
#include "core/io/Npy.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

/// One line of a segment's CSV: step, x, y (17 significant digits), X, Y (exact).
void writeCsvLine(std::ostream& out, std::uint64_t step, const PhysicalPoint& p, const UnitState& z) {
  const std::string line = io::formatC("%llu,%.17g,%.17g,%llu,%llu\n", static_cast<unsigned long long>(step),
                static_cast<double>(p.x), static_cast<double>(p.y), static_cast<unsigned long long>(z.X),
                                       static_cast<unsigned long long>(z.Y));
  out << line;
}

constexpr const char* kCsvHeader = "step,x,y,X,Y\n";

}  // namespace

std::size_t SegmentTrace::indexNear(std::uint64_t step) const noexcept {
  if (states.empty()) return 0;
  if (step >= steps) return states.size() - 1;
  const std::size_t i = static_cast<std::size_t>((step + stride / 2) / stride);
  return std::min(i, states.size() - 1);
}

std::optional<SegmentTrace> traceSegment(const TrappingParameters& params, const SegmentRecord& record,
                                         std::uint64_t maxPoints, std::stop_token stop) {
  if (auto e = lowerBoundError("maxPoints", maxPoints, 3)) throw std::invalid_argument(*e);
  validate(params);
  SegmentTrace trace;
  trace.record = record;
  const std::uint64_t expectedSteps = record.length * params.q;
  trace.stride = expectedSteps + 1 <= maxPoints ? 1 : (expectedSteps + maxPoints - 3) / (maxPoints - 2);
  trace.states.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(expectedSteps / trace.stride + 2, maxPoints)));
  UnitState last;
  std::uint64_t lastStep = 0;
  const auto blocks = replaySegmentUntil(params, record, [&](std::uint64_t step, const UnitState& z) {
    last = z;
    lastStep = step;
    // A record of other parameters could run longer than announced: never keep more than maxPoints states.
    if (step % trace.stride == 0 && trace.states.size() + 1 < maxPoints) trace.states.push_back(z);
    return true;
  }, stop);
  if (!blocks) return std::nullopt;
  trace.blocks = *blocks;
  trace.steps = lastStep;
  if (trace.states.empty() || lastStep % trace.stride != 0 || (lastStep / trace.stride) + 1 != trace.states.size())
    trace.states.push_back(last);
  const FixedPointMap map(params.map);
  trace.points.reserve(trace.states.size());
  for (const UnitState& z : trace.states) trace.points.push_back(map.toPhysical(z));
  return trace;
}

std::optional<std::vector<PhysicalPoint>> segmentPrefix(const TrappingParameters& params, const SegmentRecord& record,
                                                        std::uint64_t count, std::stop_token stop) {
  validate(params);
  const FixedPointMap map(params.map);
  std::vector<PhysicalPoint> points;
  points.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(count, record.length * params.q + 1)));
  const auto blocks = replaySegmentUntil(params, record, [&](std::uint64_t, const UnitState& z) {
    if (points.size() >= count) return false;
    points.push_back(map.toPhysical(z));
    return true;
  }, stop);
  if (!blocks) return std::nullopt;
  return points;
}

SegmentRegion dwellRegion(std::span<const PhysicalPoint> points, double fraction, int grid, double margin) {
  if (points.empty()) throw std::invalid_argument("dwellRegion: no points");
  if (auto e = realIntervalError("fraction", fraction, 0, true, 1)) throw std::invalid_argument("dwellRegion: " + *e);
  if (auto e = lowerBoundError("grid", grid, 1)) throw std::invalid_argument("dwellRegion: " + *e);
  if (auto e = realIntervalError("margin", margin, 0, false, std::numeric_limits<double>::infinity())) throw std::invalid_argument("dwellRegion: " + *e);
  long double x0 = points.front().x, x1 = x0, y0 = points.front().y, y1 = y0;
  for (const PhysicalPoint& p : points) {
    x0 = std::min(x0, p.x);
    x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y);
    y1 = std::max(y1, p.y);
  }
  const auto n = static_cast<std::size_t>(grid);
  auto cellOf = [&](long double v, long double lo, long double hi) {
    if (hi <= lo) return std::size_t{0};
    const long double c = std::floor((v - lo) / (hi - lo) * static_cast<long double>(grid));
    return static_cast<std::size_t>(std::clamp(c, 0.0L, static_cast<long double>(grid - 1)));
  };
  std::vector<std::uint64_t> counts(n * n, 0);
  for (const PhysicalPoint& p : points) counts[cellOf(p.y, y0, y1) * n + cellOf(p.x, x0, x1)] += 1;
  std::vector<std::size_t> order(counts.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  // Fullest first; ties by cell index so that the region does not depend on the sort's whims.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return counts[a] != counts[b] ? counts[a] > counts[b] : a < b;
  });
  const auto wanted = static_cast<std::uint64_t>(std::ceil(fraction * static_cast<double>(points.size())));
  std::uint64_t taken = 0;
  std::size_t cx0 = n, cx1 = 0, cy0 = n, cy1 = 0;
  for (std::size_t cell : order) {
    if (taken >= wanted || counts[cell] == 0) break;
    taken += counts[cell];
    cx0 = std::min(cx0, cell % n);
    cx1 = std::max(cx1, cell % n);
    cy0 = std::min(cy0, cell / n);
    cy1 = std::max(cy1, cell / n);
  }
  const long double cw = (x1 - x0) / static_cast<long double>(grid);
  const long double ch = (y1 - y0) / static_cast<long double>(grid);
  SegmentRegion r;
  r.x0 = x0 + cw * static_cast<long double>(cx0);
  r.x1 = x0 + cw * static_cast<long double>(cx1 + 1);
  r.y0 = y0 + ch * static_cast<long double>(cy0);
  r.y1 = y0 + ch * static_cast<long double>(cy1 + 1);
  // The cells' box may hold more than the cells taken: count what it really holds.
  std::uint64_t inside = 0;
  for (const PhysicalPoint& p : points)
    if (p.x >= r.x0 && p.x <= r.x1 && p.y >= r.y0 && p.y <= r.y1) ++inside;
  r.fraction = static_cast<double>(inside) / static_cast<double>(points.size());
  const long double mx = static_cast<long double>(margin) * r.width();
  const long double my = static_cast<long double>(margin) * r.height();
  r.x0 -= mx;
  r.x1 += mx;
  r.y0 -= my;
  r.y1 += my;
  return r;
}

SegmentRegion framedInBox(const SegmentRegion& r, const MapParameters& map, double aspect, long double minSize) {
  if (!(aspect > 0) || !std::isfinite(aspect)) throw std::invalid_argument("framedInBox: aspect must be > 0");
  if (auto e = realIntervalError("minSize", static_cast<double>(minSize), 0, false, std::numeric_limits<double>::infinity()))
    throw std::invalid_argument("framedInBox: " + *e);
  const long double a = aspect;
  long double w = std::max(r.width(), minSize);
  long double h = std::max(r.height(), minSize);
  if (w < a * h)
    w = a * h;
  else
    h = w / a;
  const long double L = map.width();
  w = std::min(w, L);
  h = std::min(h, L);
  auto place = [](long double centre, long double size, long double lo, long double hi) {
    const long double start = std::clamp(centre - size / 2, lo, hi - size);
    return std::pair{start, start + size};
  };
  SegmentRegion f = r;
  std::tie(f.x0, f.x1) = place((r.x0 + r.x1) / 2, w, static_cast<long double>(map.xmin), static_cast<long double>(map.xmax));
  std::tie(f.y0, f.y1) = place((r.y0 + r.y1) / 2, h, -L / 2, L / 2);
  return f;
}

std::optional<SegmentChain> identifySegmentChain(const TrappingParameters& params, const SegmentRecord& record,
                                                 std::uint64_t maxPoints, const IslandChainOptions& options,
                                                 std::stop_token stop) {
  auto points = segmentPrefix(params, record, maxPoints, stop);
  if (!points) return std::nullopt;
  if (points->size() < 2 * static_cast<std::size_t>(std::max(options.minPointsPerPhase, 1)))
    throw std::invalid_argument("segment of " + std::to_string(points->size()) +
                                " points is too short to identify its island chain");
  if (stop.stop_requested()) return std::nullopt;
  SegmentChain result{identifyIslandChain(params.map.K, *points, options), points->size(), {}};
  const int level = result.chain.hierarchy.size() > 1 ? result.chain.hierarchy[1] : 1;
  result.island = islandRegion(*points, level);
  return result;
}

SegmentRegion islandRegion(std::span<const PhysicalPoint> consecutive, int level, double fraction, double margin) {
  if (auto e = lowerBoundError("level", level, 1)) throw std::invalid_argument("islandRegion: " + *e);
  std::vector<PhysicalPoint> sub;
  sub.reserve(consecutive.size() / static_cast<std::size_t>(level) + 1);
  for (std::size_t i = 0; i < consecutive.size(); i += static_cast<std::size_t>(level)) sub.push_back(consecutive[i]);
  return dwellRegion(sub, fraction, 64, margin);
}

void writeSegmentCsv(const std::string& path, const SegmentTrace& trace) {
  io::AtomicOutputFile file(path);
  std::ostream& out = file.stream();
  out << kCsvHeader;
  for (std::size_t i = 0; i < trace.states.size(); ++i) writeCsvLine(out, trace.stepAt(i), trace.points[i], trace.states[i]);
  file.commit();
}

std::optional<std::string> strideError(std::uint64_t stride) {
  return lowerBoundError("stride", stride, 1);
}

std::uint64_t writeSegmentCsv(const std::string& path, const TrappingParameters& params, const SegmentRecord& record,
                              std::uint64_t stride) {
  if (auto e = strideError(stride)) throw std::invalid_argument(*e);
  validate(params);
  const FixedPointMap map(params.map);
  // Streamed into a temporary beside `path`, published only when the replay ended where the record says: a
  // replay mismatch, a full disk or a kill leaves the old file (or none), never a truncated one.
  io::AtomicOutputFile file(path);
  std::ostream& out = file.stream();
  out << kCsvHeader;
  // The last step is only known when the replay ends: keep the latest state not yet written.
  UnitState pending;
  std::uint64_t pendingStep = 0;
  bool havePending = false;
  const std::uint64_t blocks = replaySegment(params, record, [&](std::uint64_t step, const UnitState& z) {
    if (step % stride == 0) {
      writeCsvLine(out, step, map.toPhysical(z), z);
      havePending = false;
    } else {
      pending = z;
      pendingStep = step;
      havePending = true;
    }
  });
  if (havePending) writeCsvLine(out, pendingStep, map.toPhysical(pending), pending);
  file.commit();
  return blocks;
}

void writeSegmentNpy(const std::string& path, const SegmentTrace& trace) {
  std::vector<double> data;
  data.reserve(trace.states.size() * 3);
  for (std::size_t i = 0; i < trace.states.size(); ++i) {
    data.push_back(static_cast<double>(trace.stepAt(i)));
    data.push_back(static_cast<double>(trace.points[i].x));
    data.push_back(static_cast<double>(trace.points[i].y));
  }
  writeNpy(path, data, trace.states.size(), 3);
}

}  // namespace archipelago
