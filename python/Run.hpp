// The trapping run Python holds (archipelago.Run, bound in bind_run.cpp), shared with the bindings that read a run
// (bind_scan.cpp): one C++ type, so that pybind11 converts it in every file.

#pragma once

#include <stdexcept>

#include "core/run/TrappingRun.hpp"

namespace archipelago::bindings {

/// A trapping run held by Python: a TrappingState (core/run/TrappingRun.hpp).
/// Every access holds the GIL except advance()'s computation, which marks the run busy meanwhile.
struct Run {
  TrappingState state;
  bool valid = true;
  bool busy = false;

  /// Call before every access: ValueError while advance() computes, RuntimeError once an error lost the run.
  void check() const {
    if (busy) throw std::invalid_argument("this run is being advanced (advance() is running)");
    if (!valid) throw std::runtime_error("this run was lost by an error while computing");
  }
};

}  // namespace archipelago::bindings
