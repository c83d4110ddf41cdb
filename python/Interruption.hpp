// Ctrl-C for every long call of the Python module (issue #23): the one way a computation that runs without the GIL
// is stopped by a pending Python exception (KeyboardInterrupt, or one raised by a progress callback) and raises it
// once the computation has returned.
//
// Python runs a signal's handler only when the main thread runs Python code; a computation of core that holds no GIL
// would run on for minutes after Ctrl-C.  So a check() takes the GIL back briefly: PyErr_CheckSignals() runs the
// handler (KeyboardInterrupt) and the progress callback, if any, runs; an exception from either is kept (the
// interpreter stays clean while core finishes), the stop_source is requested, and core stops at its next check of
// the token.  Core answers a stop by returning a consistent state (a run, a tail sampler, a map) or by throwing (a
// periodic-orbit search, a manifold); either way the kept exception is raised once the work has returned, after the
// caller saved what it must (a checkpoint).  Two ways to call check():
//   - at core's progress points, where a Python progress callback must run too (Run.advance, tail, indicator): the
//     observer calls check(progress, report);
//   - every 50 ms from the calling thread while the work runs on a worker thread (withoutGilPolled()): for work with
//     no Python callback (stochastic_area, portrait, periodic_orbit, manifold, flux, rotation, rotation_profile,
//     orbit_measures: interruptible()), and for work whose progress points are far apart (tail, indicator: a unit of
//     stage 0 or a round of pixels lasted up to 70 s, and Ctrl-C waited for it, issue 36), whose observer then
//     runs check(progress, report) on the worker thread.

#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <future>
#include <optional>
#include <stop_token>
#include <type_traits>
#include <utility>

namespace archipelago::bindings {

namespace py = pybind11;

/// A stop_source with the Python exception that requested it.  check() may be called from any thread (it takes the
/// GIL, which also guards the pending exception); withoutGil(), raisePending() and run() from the calling thread.
class Interruption {
 public:
  /// The token to hand to core.
  [[nodiscard]] std::stop_token token() const { return stopper_.get_token(); }

  /// A progress point: checks for a signal and calls progress(report()) when a progress callback was given (both
  /// with the GIL).  After the first exception it does nothing: the work is stopping.
  template <class Report>
  void check(const py::object& progress, Report&& report) {
    const py::gil_scoped_acquire gil;
    if (pending_) return;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!progress.is_none()) progress(report());
    } catch (py::error_already_set& e) {
      pending_.emplace(std::move(e));  // holds the exception until raisePending(): the interpreter stays clean
      stopper_.request_stop();
    }
  }
  /// A progress point without a progress callback: Ctrl-C only.
  void check() {
    check(py::none(), [] { return py::none(); });
  }

  /// Runs work() with the GIL released and returns its result.  When the work throws after a stop was requested
  /// (core's answer to a stop), the pending Python exception is raised in its place.  A pending exception after a
  /// normal return is left to raisePending(), so that the caller can save first.
  template <class Work>
  auto withoutGil(Work&& work) -> std::invoke_result_t<Work&> {
    std::optional<std::invoke_result_t<Work&>> result;
    try {
      const py::gil_scoped_release release;
      result.emplace(work());
    } catch (...) {
      raisePending();
      throw;
    }
    return std::move(*result);
  }

  /// withoutGil(), the work running on a worker thread as work(token()) while this thread checks for Ctrl-C every
  /// 50 ms: a stop is requested within 50 ms of the signal, and core honours it at its next look at the token.
  template <class Work>
  auto withoutGilPolled(Work&& work) -> std::invoke_result_t<Work&, std::stop_token> {
    return withoutGil([&] {
      auto done = std::async(std::launch::async, [&] { return work(token()); });
      while (done.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) check();
      return done.get();
    });
  }

  /// With the GIL held: raises the exception that stopped the work, if any.
  void raisePending() {
    if (!pending_) return;
    py::error_already_set e = std::move(*pending_);
    pending_.reset();
    throw e;
  }

  /// withoutGil(work), then the pending exception raised: for a call with nothing to save when stopped.
  template <class Work>
  auto run(Work&& work) -> std::invoke_result_t<Work&> {
    auto result = withoutGil(std::forward<Work>(work));
    raisePending();
    return result;
  }

 private:
  std::stop_source stopper_;
  std::optional<py::error_already_set> pending_;
};

/// Runs work(stop), a computation of core with no Python callback, on a worker thread with the GIL released, the
/// calling thread checking for Ctrl-C every 50 ms meanwhile; returns its result.  KeyboardInterrupt when Ctrl-C
/// stopped it, else the work's own exception.
template <class Work>
auto interruptible(Work work) -> std::invoke_result_t<Work&, std::stop_token> {
  Interruption interruption;
  auto result = interruption.withoutGilPolled(work);
  interruption.raisePending();
  return result;
}

}  // namespace archipelago::bindings
