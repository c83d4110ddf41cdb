#include "MpiCommon.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include <dlfcn.h>

namespace archipelago::mpi {

World world() {
  World w;
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size);
  return w;
}

void agree(const World& w, bool ok, const std::string& message) {
  int mine = ok ? 1 : 0;
  int all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (all == 1) return;
  // The lowest failing rank's message goes to rank 0.
  int failing = ok ? INT_MAX : w.rank;
  int first = 0;
  MPI_Allreduce(&failing, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  std::string text = message;
  if (first != 0) {
    if (w.rank == first) {
      const auto n = static_cast<int>(std::min<std::size_t>(text.size(), 4096));
      MPI_Send(text.data(), n, MPI_CHAR, 0, 7, MPI_COMM_WORLD);
    } else if (w.rank == 0) {
      MPI_Status st;
      MPI_Probe(first, 7, MPI_COMM_WORLD, &st);
      int n = 0;
      MPI_Get_count(&st, MPI_CHAR, &n);
      text.assign(static_cast<std::size_t>(n), '\0');
      MPI_Recv(text.data(), n, MPI_CHAR, first, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
  }
  throw std::runtime_error(first == 0 ? text : "rank " + std::to_string(first) + ": " + text);
}

void sendText(const std::string& text, int dest) {
  const std::uint64_t n = text.size();
  MPI_Send(&n, 1, MPI_UINT64_T, dest, 1, MPI_COMM_WORLD);
  for (std::uint64_t at = 0; at < n; at += INT_MAX / 2) {
    const auto piece = static_cast<int>(std::min<std::uint64_t>(n - at, INT_MAX / 2));
    MPI_Send(text.data() + at, piece, MPI_CHAR, dest, 2, MPI_COMM_WORLD);
  }
}

std::string receiveText(int source) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, source, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  std::string text(n, '\0');
  for (std::uint64_t at = 0; at < n; at += INT_MAX / 2) {
    const auto piece = static_cast<int>(std::min<std::uint64_t>(n - at, INT_MAX / 2));
    MPI_Recv(text.data() + at, piece, MPI_CHAR, source, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
  return text;
}

void waitWithoutSpinning(MPI_Request& request) {
  int done = 0;
  MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  while (done == 0) {
    std::this_thread::sleep_for(std::chrono::microseconds(100));
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  }
}

bool MpiRanks::all(bool mine) {
  int one = mine ? 1 : 0;
  int every = 0;
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallreduce(&one, &every, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &request);
  waitWithoutSpinning(request);  // ranks that finish early do not spin while the others compute
  return every == 1;
}

std::vector<std::string> MpiRanks::gather(const std::string& text) {
  std::vector<std::string> texts;
  if (w_.rank != 0) sendText(text, 0);
  else
    for (int r = 1; r < w_.size; ++r) texts.push_back(receiveText(r));
  return texts;
}

int endJob(int status) {
  std::fflush(stdout);
  std::fflush(stderr);
  int worst = 0;
  MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);  // every rank here: its lines are written
  if (worst == 0) {
    MPI_Finalize();
    return 0;
  }
  // PMIx_Abort(status, message, procs, nprocs): the PMIx standard's end of a job (Open MPI's mpirun, Slurm's srun
  // --mpi=pmix), looked up where the MPI library loaded it; no message, every process.  It returns once the launcher
  // has the request; the launcher then ends every rank, which waits for it (Ctrl-C and SIGTERM end it at once now).
  using PmixAbort = int (*)(int, const char*, void*, std::size_t);
  const auto pmixAbort = reinterpret_cast<PmixAbort>(::dlsym(RTLD_DEFAULT, "PMIx_Abort"));
  if (pmixAbort == nullptr) {
    MPI_Finalize();
    return worst;
  }
  if (world().rank == 0 && pmixAbort(worst, nullptr, nullptr, 0) != 0)
    MPI_Abort(MPI_COMM_WORLD, worst);  // PMIx refused: MPI's own abort, with its banner
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  for (int waited = 0; waited < 600; ++waited) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::_Exit(worst);  // not ended within a minute: the status, whatever the launcher says
}

}  // namespace archipelago::mpi
