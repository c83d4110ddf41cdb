#include "MpiTail.hpp"

#include <mpi.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "MpiCommon.hpp"
#include "core/tail/TailFile.hpp"

namespace archipelago::mpi {

namespace {

/// The slice file of rank r of R beside NAME: "tail.json" → "tail.slice-1-of-4.json" (the extension kept last).
std::string sliceName(const std::string& name, int rank, int size) {
  const std::filesystem::path p(name);
  const std::string tag = ".slice-" + std::to_string(rank) + "-of-" + std::to_string(size);
  if (p.extension() == ".json") return (p.parent_path() / (p.stem().string() + tag + ".json")).string();
  return name + tag;
}

}  // namespace

int mpiTail(cli::TailOptions& o, const CLI::App& cmd) {
  const World w = world();
  if (o.printLevels) {
    if (w.rank == 0) (void)cli::prepareTail(o, cmd, std::nullopt);
    return 0;
  }
  if (w.rank != 0) {  // rank 0 shows its own slice's progress, the merged result and the warnings, once
    o.quiet = true;
    o.warnings = false;
  }
  const std::string checkpointBase = o.checkpoint.empty() ? o.out : o.checkpoint;
  const std::string checkpoint = sliceName(checkpointBase, w.rank, w.size);
  const std::string resume = o.resume.empty() ? std::string() : sliceName(o.resume, w.rank, w.size);
  cli::PreparedTail job;
  std::vector<io::FileLock> locks;
  together(w, [&] {
    if (!resume.empty() && !std::filesystem::exists(resume))
      throw std::invalid_argument("no slice file " + resume + ": resume " + o.resume +
                                  " on the number of ranks that wrote its slices (" + std::to_string(w.size) +
                                  " ranks look for NAME.slice-r-of-" + std::to_string(w.size) + ".json)");
    std::optional<ReplicaRange> slice;
    if (o.resume.empty()) slice = replicaSlice(o.request.replicas, static_cast<std::uint32_t>(w.rank),
                                               static_cast<std::uint32_t>(w.size));
    if (w.rank == 0) io::checkWritableTarget(o.out);
    job = cli::prepareTail(o, cmd, slice, resume);
    const ReplicaRange mine = replicaSlice(job.state.request.replicas, static_cast<std::uint32_t>(w.rank),
                                           static_cast<std::uint32_t>(w.size));
    if (job.state.firstReplica != mine.first || job.state.replicas.size() != mine.count)
      throw std::invalid_argument(resume + " is not slice " + std::to_string(w.rank) + " of " + std::to_string(w.size));
    locks = cli::lockRunFiles(checkpoint, checkpoint, resume);
  });
  LastCheckpoint last{resume, 0};
  TailState state = cli::runTailSession(std::move(job.state), o, checkpoint, last);
  // Every rank writes its slice, finished or not: the resume point of an interrupted job, and safe until merged.
  together(w, [&] { cli::saveTail(checkpoint, state, last); });

  int mine = state.finished() ? 1 : 0, all = 0;
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &request);
  waitWithoutSpinning(request);  // ranks that finish early do not spin while the others compute
  if (all == 0) {
    if (w.rank == 0)
      std::fprintf(stderr,
                   "interrupted: each rank's slice written to %s (resume with mpirun -n %d archipelago-mpi tail "
                   "--resume %s)\n",
                   sliceName(checkpointBase, 0, w.size).c_str(), w.size, checkpointBase.c_str());
    return 130;
  }
  int status = 0;
  if (w.rank != 0) {
    sendText(tailFileText(state), 0);
  } else {
    std::vector<TailState> slices;
    slices.push_back(std::move(state));
    std::string error;
    for (int r = 1; r < w.size; ++r) {
      const std::string text = receiveText(r);
      try {
        if (error.empty()) slices.push_back(parseTailFile(text));
      } catch (const std::exception& e) {
        error = "rank " + std::to_string(r) + "'s slice: " + e.what();
      }
    }
    try {
      if (!error.empty()) throw std::runtime_error(error);
      const TailState merged = mergeTailSlices(std::move(slices));
      saveTailFile(o.out, merged);
      for (int r = 0; r < w.size; ++r) {
        std::error_code ec;
        std::filesystem::remove(sliceName(checkpointBase, r, w.size), ec);  // merged: the slices are in --out
      }
      cli::reportTail(merged, o, job.runs);
      if (!o.quiet) {
        const TailResult result = tailResult(merged);
        std::fprintf(stderr,
                     "done: %zu levels, the largest reliable t = %.4g; %.3g steps in %.1f s of %d ranks (%s kernel); "
                     "wrote %s\n",
                     result.levels.size(), largestReliableT(result), result.steps, merged.elapsedSeconds, w.size,
                     merged.kernel.c_str(), o.out.c_str());
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "ERROR: %s (the slices are kept: %s, …)\n", e.what(),
                   sliceName(checkpointBase, 0, w.size).c_str());
      status = 1;
    }
  }
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return status;
}

}  // namespace archipelago::mpi
