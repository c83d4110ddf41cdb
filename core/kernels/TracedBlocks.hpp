#pragma once
/// \file TracedBlocks.hpp
/// \brief Trapping blocks of a group of orbits with their q steps computed by a path's orbit kernel, every
/// point handed to a visitor: for callers that need the points of trapping orbits but not their segments (b₂).
///
/// The block is BlockKernel.hpp's: enterBlock() (length + 1, the randomizing zone), q steps of N⁻¹, block + 1,
/// so the states, draws and blocks are those of advanceBlockVisiting() and of trapping runs, bit for bit.  An
/// OrbitKernel reports no wraps, so segments are not closed here (length keeps growing): a caller that needs
/// where segments end uses advanceBlockVisiting() or a BlockKernel.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/kernels/VectorKernels.hpp"
#include "core/trapping/BlockKernel.hpp"

namespace archipelago {

/// Advances `orbits` (indices firstOrbit, firstOrbit + 1, …) by `blocks` blocks, the steps computed by `steps`
/// (any path's OrbitKernel: all give the same states).  After each block, visit(trace) sees its q·n states,
/// trace[j·n + i] after step j of orbit i (n = orbits.size()).
template <class Visit>
void advanceBlocksTraced(const KernelSettings& k, OrbitKernel steps, std::span<OrbitState> orbits,
                         std::uint64_t firstOrbit, std::uint64_t blocks, Visit&& visit) {
  const std::size_t n = orbits.size();
  std::vector<UnitState> z(n), trace(n * k.q);
  for (std::uint64_t b = 0; b < blocks; ++b) {
    for (std::size_t i = 0; i < n; ++i) {
      (void)enterBlock(k, firstOrbit + i, orbits[i]);
      z[i] = orbits[i].z;
    }
    steps(k.coefficients, MapDirection::backward, z, k.q, trace.data());
    for (std::size_t i = 0; i < n; ++i) {
      orbits[i].z = z[i];
      orbits[i].block += 1;
    }
    visit(std::span<const UnitState>(trace));
  }
}

}  // namespace archipelago
