// SimdDriver.inl — the loops shared by the vector paths (KernelAvx2.cpp, KernelAvx512Ifma.cpp).
//
// Each of those files includes this one inside an anonymous namespace and inside its target-attribute region,
// so every function here is compiled once per instruction set with internal linkage (no ODR merging of an
// AVX-512 copy into the AVX2 path or into generic code).  It includes nothing itself.
//
// A SIMD policy `Simd` provides:
//   Vec, kLanes                       the vector type and its number of 64-bit lanes;
//   Constants(coefficients, Xr)       broadcast map coefficients, masks and the randomizing threshold;
//   load/store/zero                   unaligned 64-bit lane moves;
//   backward(c, X, Y, wrapBits)       one N⁻¹ step; ORs into wrapBits a word whose bits ≥ 52 are set on a wrap;
//   forward(c, X, Y)                  one N step;
//   atMost(c, X) -> unsigned          bit l set when lane l has X ≤ Xr (the randomizing zone);
//   wrapped(c, wrapBits) -> unsigned  bit l set when lane l wrapped;
//   randomize(c, lanes, key, D, Y)    for the lanes in `lanes`: D ← D + 1, Y ← (Y + orbitDraw(key, D)) mod 2^52.

/// Runs `blocks` trapping blocks on n ≤ V·kLanes orbits held in V vectors (appendix B, steps 5–9).
///
/// The hot loop carries only X, Y and a wrap accumulator per vector.  The per-lane bookkeeping of
/// advanceOneBlock() is kept out of it: a lane's open-segment length is (blocks done) − (block at which the
/// segment began), so nothing is counted per block, and the start state, block and draw counters are
/// touched only when a lane's segment ends — a per-block test of the ended mask that is almost always zero
/// at large q and cheap at q = 1.
template <class Simd, int V>
void advanceGroup(const typename Simd::Constants& c, const KernelSettings& k, OrbitState* orbits, std::size_t n,
                  std::uint64_t firstOrbit, std::uint64_t blocks, SegmentSink& sink) {
  using Vec = typename Simd::Vec;
  constexpr std::size_t W = Simd::kLanes;
  constexpr std::size_t L = W * V;
  alignas(64) std::uint64_t xs[L], ys[L], draws[L], keys[L];
  std::uint64_t segmentBegin[L], firstBlock[L];  // segmentBegin: local block index where the open segment began
  for (std::size_t l = 0; l < L; ++l) {
    if (l < n) {
      const OrbitState& s = orbits[l];
      xs[l] = s.z.X;
      ys[l] = s.z.Y;
      draws[l] = s.draws;
      keys[l] = orbitKey(k.seed, firstOrbit + l);
      segmentBegin[l] = std::uint64_t{0} - s.length;  // modulo 2^64: (b + 1) − segmentBegin = length
      firstBlock[l] = s.block;
    } else {  // padding lanes: computed, never recorded nor stored
      xs[l] = ys[l] = draws[l] = keys[l] = segmentBegin[l] = firstBlock[l] = 0;
    }
  }
  Vec X[V], Y[V], D[V], key[V];
  unsigned active[V];
  for (int v = 0; v < V; ++v) {
    X[v] = Simd::load(xs + v * W);
    Y[v] = Simd::load(ys + v * W);
    D[v] = Simd::load(draws + v * W);
    key[v] = Simd::load(keys + v * W);
    const std::size_t begin = static_cast<std::size_t>(v) * W;
    const std::size_t inVector = n > begin ? std::min(W, n - begin) : 0;
    active[v] = (1u << inVector) - 1u;
  }

  const std::uint32_t q = k.q;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    unsigned zone[V];
    unsigned anyZone = 0;
    for (int v = 0; v < V; ++v) {
      zone[v] = Simd::atMost(c, X[v]) & active[v];
      anyZone |= zone[v];
    }
    if (anyZone) [[unlikely]] {  // appendix B, 6.1–6.2: Y ← Y + U in the zone; the segment ends
      for (int v = 0; v < V; ++v)
        if (zone[v]) Simd::randomize(c, zone[v], key[v], D[v], Y[v]);
    }
    Vec wrapBits[V];
    for (int v = 0; v < V; ++v) wrapBits[v] = Simd::zero();
    for (std::uint32_t j = 0; j < q; ++j)
      for (int v = 0; v < V; ++v) Simd::backward(c, X[v], Y[v], wrapBits[v]);
    unsigned ended[V];
    unsigned anyEnded = 0;
    for (int v = 0; v < V; ++v) {
      ended[v] = (Simd::wrapped(c, wrapBits[v]) | zone[v]) & active[v];
      anyEnded |= ended[v];
    }
    if (anyEnded) {
      const std::uint64_t after = b + 1;  // local blocks done after this one
      for (int v = 0; v < V; ++v) {
        if (!ended[v]) continue;
        Simd::store(xs + v * W, X[v]);
        Simd::store(ys + v * W, Y[v]);
        Simd::store(draws + v * W, D[v]);
        for (unsigned bits = ended[v]; bits; bits &= bits - 1) {
          const std::size_t l = v * W + static_cast<std::size_t>(__builtin_ctz(bits));
          OrbitState& s = orbits[l];
          sink.record(firstOrbit + l, after - segmentBegin[l], s.start);
          s.start = {{xs[l], ys[l]}, firstBlock[l] + after, draws[l]};
          segmentBegin[l] = after;
        }
      }
    }
  }

  for (int v = 0; v < V; ++v) {
    Simd::store(xs + v * W, X[v]);
    Simd::store(ys + v * W, Y[v]);
    Simd::store(draws + v * W, D[v]);
  }
  for (std::size_t l = 0; l < n; ++l) {
    OrbitState& s = orbits[l];
    s.z = {xs[l], ys[l]};
    s.draws = draws[l];
    s.block = firstBlock[l] + blocks;
    s.length = blocks - segmentBegin[l];
  }
}

/// Chooses the number of vectors (1 … V) that holds n orbits, so a small group computes no empty vectors.
template <class Simd, int V>
void advanceGroupOfSize(std::size_t vectors, const typename Simd::Constants& c, const KernelSettings& k,
                        OrbitState* orbits, std::size_t n, std::uint64_t firstOrbit, std::uint64_t blocks,
                        SegmentSink& sink) {
  if constexpr (V > 1) {
    if (vectors < static_cast<std::size_t>(V)) {
      advanceGroupOfSize<Simd, V - 1>(vectors, c, k, orbits, n, firstOrbit, blocks, sink);
      return;
    }
  }
  advanceGroup<Simd, V>(c, k, orbits, n, firstOrbit, blocks, sink);
}

template <class Simd, int V>
void advanceBlocksWith(const KernelSettings& k, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                       std::uint64_t blocks, SegmentSink& sink) {
  const typename Simd::Constants c(k.coefficients, k.randomizingX);
  constexpr std::size_t group = Simd::kLanes * V;
  for (std::size_t first = 0; first < orbits.size(); first += group) {
    const std::size_t n = std::min(group, orbits.size() - first);
    advanceGroupOfSize<Simd, V>((n + Simd::kLanes - 1) / Simd::kLanes, c, k, orbits.data() + first, n,
                                firstOrbit + first, blocks, sink);
  }
}

/// Plain iteration of n ≤ V·kLanes orbits; trace as in OrbitKernel, with row length `stride`.
template <class Simd, int V>
void iterateGroup(const typename Simd::Constants& c, MapDirection direction, UnitState* orbits, std::size_t n,
                  std::uint64_t steps, UnitState* trace, std::size_t stride) {
  using Vec = typename Simd::Vec;
  constexpr std::size_t W = Simd::kLanes;
  constexpr std::size_t L = W * V;
  alignas(64) std::uint64_t xs[L], ys[L];
  for (std::size_t l = 0; l < L; ++l) {
    xs[l] = l < n ? orbits[l].X : 0;
    ys[l] = l < n ? orbits[l].Y : 0;
  }
  Vec X[V], Y[V];
  for (int v = 0; v < V; ++v) {
    X[v] = Simd::load(xs + v * W);
    Y[v] = Simd::load(ys + v * W);
  }
  const auto record = [&](std::uint64_t j) {
    for (int v = 0; v < V; ++v) {
      Simd::store(xs + v * W, X[v]);
      Simd::store(ys + v * W, Y[v]);
    }
    UnitState* row = trace + j * stride;
    for (std::size_t l = 0; l < n; ++l) row[l] = {xs[l], ys[l]};
  };
  if (direction == MapDirection::backward) {
    Vec unused[V];
    for (int v = 0; v < V; ++v) unused[v] = Simd::zero();
    for (std::uint64_t j = 0; j < steps; ++j) {
      for (int v = 0; v < V; ++v) Simd::backward(c, X[v], Y[v], unused[v]);
      if (trace) record(j);
    }
  } else {
    for (std::uint64_t j = 0; j < steps; ++j) {
      for (int v = 0; v < V; ++v) Simd::forward(c, X[v], Y[v]);
      if (trace) record(j);
    }
  }
  for (int v = 0; v < V; ++v) {
    Simd::store(xs + v * W, X[v]);
    Simd::store(ys + v * W, Y[v]);
  }
  for (std::size_t l = 0; l < n; ++l) orbits[l] = {xs[l], ys[l]};
}

template <class Simd, int V>
void iterateGroupOfSize(std::size_t vectors, const typename Simd::Constants& c, MapDirection direction,
                        UnitState* orbits, std::size_t n, std::uint64_t steps, UnitState* trace, std::size_t stride) {
  if constexpr (V > 1) {
    if (vectors < static_cast<std::size_t>(V)) {
      iterateGroupOfSize<Simd, V - 1>(vectors, c, direction, orbits, n, steps, trace, stride);
      return;
    }
  }
  iterateGroup<Simd, V>(c, direction, orbits, n, steps, trace, stride);
}

template <class Simd, int V>
void iterateOrbitsWith(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                       std::uint64_t steps, UnitState* trace) {
  const typename Simd::Constants c(coefficients, 0);
  constexpr std::size_t group = Simd::kLanes * V;
  for (std::size_t first = 0; first < orbits.size(); first += group) {
    const std::size_t n = std::min(group, orbits.size() - first);
    iterateGroupOfSize<Simd, V>((n + Simd::kLanes - 1) / Simd::kLanes, c, direction, orbits.data() + first, n,
                                steps, trace ? trace + first : nullptr, orbits.size());
  }
}
