#pragma once
/// \file Ranks.hpp
/// \brief The processes a job's work is shared among (issue 51): archipelago-mpi's ranks, or one process.  A job of
/// core speaks to its ranks only through this interface — app/mpi implements it with MPI (MpiRanks), and OneProcess
/// is the trivial one of the command line, Python and the GUI — so every front end runs the same job.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace archipelago {

class Ranks {
public:
  virtual ~Ranks() = default;
  /// This process's rank, 0 to size() − 1.
  [[nodiscard]] virtual int rank() const = 0;
  [[nodiscard]] virtual int size() const = 0;
  /// Whether the job's work is sliced over the ranks, each writing its slice (archipelago-mpi, even on one rank),
  /// rather than done whole by this process.
  [[nodiscard]] virtual bool sliced() const = 0;
  /// Every rank's `ok`: returns when all are; otherwise throws std::runtime_error on every rank, with the lowest
  /// failing rank's message on rank 0 ("rank r: …" when r is not 0).
  virtual void agree(bool ok, const std::string& message) = 0;
  /// Whether `mine` holds on every rank (a rank that arrives first waits without taking a core from the others).
  [[nodiscard]] virtual bool all(bool mine) = 0;
  /// On rank 0: the texts of ranks 1 … size() − 1, in order (its own `text` is not sent); on the others: `text`
  /// sent to rank 0, and nothing returned.
  [[nodiscard]] virtual std::vector<std::string> gather(const std::string& text) = 0;
};

/// One process: rank 0 of 1, doing the whole job.
class OneProcess final : public Ranks {
public:
  [[nodiscard]] int rank() const override { return 0; }
  [[nodiscard]] int size() const override { return 1; }
  [[nodiscard]] bool sliced() const override { return false; }
  void agree(bool ok, const std::string& message) override {
    if (!ok) throw std::runtime_error(message);
  }
  [[nodiscard]] bool all(bool mine) override { return mine; }
  [[nodiscard]] std::vector<std::string> gather(const std::string&) override { return {}; }
};

/// Runs `f` on every rank; an exception on any rank becomes one error on all (ranks.agree()).
template <class F>
void together(Ranks& ranks, F&& f) {
  std::string message;
  bool ok = true;
  try {
    std::forward<F>(f)();
  } catch (const std::exception& e) {
    ok = false;
    message = e.what();
  }
  ranks.agree(ok, message);
}

}  // namespace archipelago
