#include <gtest/gtest.h>
#include <cstdio>
#include <chrono>
#include "core/measures/IndicatorMap.hpp"
#include "core/portrait/StochasticArea.hpp"
using namespace archipelago;
TEST(Scratch, Share) {
  MapParameters box{0.1, -0.8, 0.5};
  auto t0 = std::chrono::steady_clock::now();
  StochasticAreaRequest a; a.map = box; a.iterations = 1ull<<27; a.firstCheckpoint = a.iterations;
  auto b2 = computeStochasticArea(a);
  std::printf("b2 %.5f %.2fs\n", b2.b2(), std::chrono::duration<double>(std::chrono::steady_clock::now()-t0).count());
  for (auto [N, T] : {std::pair{96, 10000ull}, std::pair{96, 20000ull}, std::pair{128, 20000ull}, std::pair{128, 10000ull}}) {
    IndicatorRequest r; r.measure.map = box; r.measure.kind = IndicatorKind::Dig; r.measure.iterations = T; r.width = r.height = N; r.passes = 1;
    auto res = computeIndicatorMap(r);
    int chaotic = 0, escV = 0, regV = 0, chaoNV = 0, esc = 0;
    for (int row = 0; row < N; ++row) for (int col = 0; col < N; ++col) {
      const UnitState z = indicatorPixelStart(r.view, N, N, col, row);
      const bool visited = b2.visited[(z.Y >> 42) * 1024 + (z.X >> 42)];
      auto v = res.raster.verdicts[row * N + col];
      chaotic += v == OrbitVerdict::Chaotic; esc += v == OrbitVerdict::Escaping;
      escV += v == OrbitVerdict::Escaping && visited; regV += v == OrbitVerdict::Regular && visited; chaoNV += v == OrbitVerdict::Chaotic && !visited;
    }
    double n = N*N;
    std::printf("N=%d T=%llu chaotic %.5f esc %.5f escV %.5f regV %.5f chaoNV %.5f  chaotic+escV %.5f  %.2fs\n", N, (unsigned long long)T, chaotic/n, esc/n, escV/n, regV/n, chaoNV/n, (chaotic+escV)/n, res.seconds);
  }
}
