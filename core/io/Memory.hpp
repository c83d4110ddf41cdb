#pragma once
/// \file Memory.hpp
/// \brief How much memory this process may still take, and the check made before a large allocation: a
/// computation whose documented maximum does not fit the machine is refused with its size, before it starts,
/// instead of being killed by the kernel or exhausting the machine (issue #23).

#include <cstdint>
#include <stdexcept>
#include <string>

namespace archipelago::io {

/// The memory this process can still take, in bytes: the smaller of MemAvailable (/proc/meminfo) and what is
/// left of RLIMIT_AS; UINTMAX_MAX when neither is known.
[[nodiscard]] std::uintmax_t availableMemoryBytes();

/// What checkMemory throws (a std::runtime_error: front ends print it as any error; Python raises MemoryError).
struct NotEnoughMemory : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws NotEnoughMemory("<what> needs about N MiB of memory but only M MiB are available") when `bytes`
/// exceeds availableMemoryBytes().  For the documented maxima of long computations (a Markov matrix, an
/// orbit held whole) checked before work starts.
void checkMemory(std::uintmax_t bytes, const std::string& what);

}  // namespace archipelago::io
