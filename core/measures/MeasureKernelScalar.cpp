// The portable orbit-measure kernel (MeasureKernels.hpp): the reference the vector paths are tested against.
// Orbits are stepped by ScalarStep (map/ScalarStep.hpp) eight at a time, as two "vectors" of four doubles
// that are plain arrays (the compiler may use SSE2 for them: every operation is still one IEEE operation per
// lane, so the sums are those of any other path).

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "core/map/ScalarStep.hpp"
#include "core/measures/MeasureKernels.hpp"

namespace archipelago::measures {
namespace {

#include "core/measures/MeasureMath.inl"

constexpr std::size_t kWidth = 4;

struct Mask4 {
  bool b[kWidth];
};
struct Index4 {
  unsigned i[kWidth];
};

/// Four doubles, operated on lane by lane.
struct Lane4 {
  double v[kWidth];
  Lane4() = default;
  Lane4(double a) : v{a, a, a, a} {}  // NOLINT: implicit broadcast, as MeasureMath.inl needs

  template <class F>
  static Lane4 map(F f) {
    Lane4 r;
    for (std::size_t l = 0; l < kWidth; ++l) r.v[l] = f(l);
    return r;
  }
  friend Lane4 operator+(Lane4 a, Lane4 b) { return map([&](std::size_t l) { return a.v[l] + b.v[l]; }); }
  friend Lane4 operator-(Lane4 a, Lane4 b) { return map([&](std::size_t l) { return a.v[l] - b.v[l]; }); }
  friend Lane4 operator*(Lane4 a, Lane4 b) { return map([&](std::size_t l) { return a.v[l] * b.v[l]; }); }
  friend Lane4 operator/(Lane4 a, Lane4 b) { return map([&](std::size_t l) { return a.v[l] / b.v[l]; }); }
  friend Mask4 operator>(Lane4 a, Lane4 b) {
    Mask4 m;
    for (std::size_t l = 0; l < kWidth; ++l) m.b[l] = a.v[l] > b.v[l];
    return m;
  }
  friend Mask4 operator<(Lane4 a, Lane4 b) {
    Mask4 m;
    for (std::size_t l = 0; l < kWidth; ++l) m.b[l] = a.v[l] < b.v[l];
    return m;
  }
  friend Lane4 absValue(Lane4 a) { return map([&](std::size_t l) { return archipelago::measures::absValue(a.v[l]); }); }
  friend Lane4 minValue(Lane4 a, Lane4 b) {
    return map([&](std::size_t l) { return archipelago::measures::minValue(a.v[l], b.v[l]); });
  }
  friend Lane4 maxValue(Lane4 a, Lane4 b) {
    return map([&](std::size_t l) { return archipelago::measures::maxValue(a.v[l], b.v[l]); });
  }
  friend Lane4 select(Mask4 m, Lane4 a, Lane4 b) { return map([&](std::size_t l) { return m.b[l] ? a.v[l] : b.v[l]; }); }
  friend Lane4 negateWhere(Mask4 m, Lane4 a) {
    return map([&](std::size_t l) { return archipelago::measures::negateWhere(m.b[l], a.v[l]); });
  }
  friend Lane4 splitExponent(Lane4 r, Lane4& mantissa) {
    return map([&](std::size_t l) { return archipelago::measures::splitExponent(r.v[l], mantissa.v[l]); });
  }
};

// Found by argument-dependent lookup on Mask4 and Index4 (not hidden friends of Lane4).
Mask4 maskXor(Mask4 a, Mask4 b) {
  Mask4 m;
  for (std::size_t l = 0; l < kWidth; ++l) m.b[l] = a.b[l] != b.b[l];
  return m;
}
Index4 offsetIndex(Mask4 mid, Mask4 far, Mask4 swapped, Mask4 cNegative) {
  Index4 r;
  for (std::size_t l = 0; l < kWidth; ++l)
    r.i[l] = archipelago::measures::offsetIndex(mid.b[l], far.b[l], swapped.b[l], cNegative.b[l]);
  return r;
}
Lane4 lookup(Index4 index, const double (&table)[16]) {
  return Lane4::map([&](std::size_t l) { return table[index.i[l]]; });
}

struct Scalar {
  using D = Lane4;
  static constexpr std::size_t kLanes = kWidth;
  static D load(const double* p) { return D::map([&](std::size_t l) { return p[l]; }); }
  static void store(double* p, D a) { std::copy(a.v, a.v + kWidth, p); }

  template <int V>
  class Stepper {
   public:
    static constexpr std::size_t kOrbits = kWidth * static_cast<std::size_t>(V);
    Stepper(const MeasureSetup& s, const std::uint64_t* xs, const std::uint64_t* ys, std::uint64_t, bool trackWraps)
        : step_(s.coefficients), trackWraps_(trackWraps) {
      std::copy(xs, xs + kOrbits, X_);
      std::copy(ys, ys + kOrbits, Y_);
    }
    void next() {
      if (trackWraps_) {
        ARCHIPELAGO_UNROLL_LANES
        for (std::size_t l = 0; l < kOrbits; ++l) step_.forward(X_[l], Y_[l], wrap_[l]);
      } else {
        ARCHIPELAGO_UNROLL_LANES
        for (std::size_t l = 0; l < kOrbits; ++l) step_.forward(X_[l], Y_[l]);
      }
    }
    [[nodiscard]] D x(int v) const { return lanes(X_, v); }
    [[nodiscard]] D y(int v) const { return lanes(Y_, v); }
    void store(std::uint64_t* xs, std::uint64_t* ys, std::uint64_t* wraps) const {
      std::copy(X_, X_ + kOrbits, xs);
      std::copy(Y_, Y_ + kOrbits, ys);
      for (std::size_t l = 0; l < kOrbits; ++l) wraps[l] |= wrap_[l] >= fixedpoint::kOne ? 1 : 0;
    }

   private:
    static D lanes(const std::uint64_t* a, int v) {
      const std::size_t o = static_cast<std::size_t>(v) * kWidth;
      return D::map([&](std::size_t l) { return static_cast<double>(static_cast<std::int64_t>(a[o + l])); });
    }
    ScalarStep step_;
    bool trackWraps_;
    std::uint64_t X_[kOrbits], Y_[kOrbits], wrap_[kOrbits] = {};
  };
};

#include "core/measures/MeasureDriver.inl"

constexpr int kVectors = 2;  // eight orbits interleaved (kernels/ScalarLanes.hpp's kScalarLanes)

}  // namespace

void measureKernelScalar(const MeasureSetup& setup, std::span<MeasureLane> lanes, std::uint64_t first,
                         std::uint64_t steps) {
  measureWith<Scalar, kVectors>(setup, lanes, first, steps);
}

}  // namespace archipelago::measures
