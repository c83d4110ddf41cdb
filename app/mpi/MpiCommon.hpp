#pragma once
/// \file MpiCommon.hpp
/// \brief What archipelago-mpi's commands share (run: MpiRun.hpp; tail: MpiTail.hpp): the world and its ranks as
/// core's jobs see them, errors agreed by every rank, text sent between ranks, waiting for a collective without
/// spinning, and the end of the job.

#include <mpi.h>

#include <string>
#include <vector>

#include "core/job/Ranks.hpp"

namespace archipelago::mpi {

struct World {
  int rank = 0;
  int size = 1;
};

/// This process's rank and the number of ranks (MPI initialized).
[[nodiscard]] World world();

/// Every rank's `ok`: returns when all are; otherwise throws std::runtime_error on every rank, with the lowest
/// failing rank's message on rank 0.
void agree(const World& w, bool ok, const std::string& message);

/// The ranks of MPI_COMM_WORLD as core's jobs see them (core/job/Ranks.hpp): each runs its slice of the job; errors
/// agreed by every rank (agree()), a collective waited for without spinning, texts gathered on rank 0.
class MpiRanks final : public Ranks {
public:
  MpiRanks() : w_(world()) {}
  [[nodiscard]] int rank() const override { return w_.rank; }
  [[nodiscard]] int size() const override { return w_.size; }
  [[nodiscard]] bool sliced() const override { return true; }
  void agree(bool ok, const std::string& message) override { mpi::agree(w_, ok, message); }
  [[nodiscard]] bool all(bool mine) override;
  [[nodiscard]] std::vector<std::string> gather(const std::string& text) override;

private:
  World w_;
};

/// The end of every rank, with the status of the job: 0, or the largest of the ranks' (issue 54, finding 8).  A
/// non-zero status ends the job once every rank has come here (rank 0's ERROR line written) through PMIx's abort,
/// which ends it with that status and no word: a rank exiting non-zero makes Open MPI's mpirun follow the ERROR line
/// with its block ("mpirun detected that one or more processes exited with non-zero status …"), and MPI_Abort with
/// its "MPI_ABORT was invoked …" banner.  Without PMIx (another MPI), MPI_Finalize and the status.
[[nodiscard]] int endJob(int status);

/// Text of any length from this rank to `dest` (sendText) and from `source` (receiveText), in pieces below
/// MPI's int counts.
void sendText(const std::string& text, int dest);
[[nodiscard]] std::string receiveText(int source);

/// MPI_Wait for a collective, polling every 100 µs and sleeping between (OpenMPI's blocking calls spin, taking a
/// core from the ranks still computing when the machine is shared or oversubscribed).
void waitWithoutSpinning(MPI_Request& request);

}  // namespace archipelago::mpi
