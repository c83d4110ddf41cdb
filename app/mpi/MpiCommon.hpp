#pragma once
/// \file MpiCommon.hpp
/// \brief What archipelago-mpi's commands share (run: MpiRun.hpp; tail: MpiTail.hpp): the world, errors agreed
/// by every rank, text sent between ranks, and waiting for a collective without spinning.

#include <mpi.h>

#include <string>

namespace archipelago::mpi {

struct World {
  int rank = 0;
  int size = 1;
};

/// This process's rank and the number of ranks (MPI initialized).
[[nodiscard]] World world();

/// An error of this rank alone (its file, its memory): printed with the rank, and the whole job aborted, since
/// the others would wait for it forever.
[[noreturn]] void abortJob(const World& w, const std::string& what);

/// Every rank's `ok`: returns when all are; otherwise throws std::runtime_error on every rank, with the lowest
/// failing rank's message on rank 0.
void agree(const World& w, bool ok, const std::string& message);

/// Runs `f` on every rank; an exception on any rank becomes one error on all (printed by rank 0).
template <class F>
void together(const World& w, F&& f) {
  std::string message;
  bool ok = true;
  try {
    f();
  } catch (const std::exception& e) {
    ok = false;
    message = e.what();
  }
  agree(w, ok, message);
}

/// Text of any length from this rank to `dest` (sendText) and from `source` (receiveText), in pieces below
/// MPI's int counts.
void sendText(const std::string& text, int dest);
[[nodiscard]] std::string receiveText(int source);

/// MPI_Wait for a collective, polling every 100 µs and sleeping between (OpenMPI's blocking calls spin, taking a
/// core from the ranks still computing when the machine is shared or oversubscribed).
void waitWithoutSpinning(MPI_Request& request);

}  // namespace archipelago::mpi
