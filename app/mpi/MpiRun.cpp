#include "MpiRun.hpp"

#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "CliCommon.hpp"
#include "MpiCommon.hpp"
#include "RunSession.hpp"
#include "core/runfile/CheckpointedRun.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/runfile/RunFileMerge.hpp"

namespace archipelago::mpi {

namespace {

using Clock = std::chrono::steady_clock;

/// Orbits of rank r of R: [⌊M·r/R⌋, ⌊M·(r+1)/R⌋) (M ≤ 2³², R < 2³¹: no overflow).
std::pair<std::uint64_t, std::uint64_t> rankRange(std::uint64_t M, int r, int R) {
  const auto u = static_cast<std::uint64_t>(R);
  return {M * static_cast<std::uint64_t>(r) / u, M * static_cast<std::uint64_t>(r + 1) / u};
}

/// The target wall time of a round of the slowest rank: the latency of a stop or checkpoint request, and the
/// interval between the ranks' synchronisations.
/// Measured (bench-mpi.sh's spec, T = 8e6, 2 ranks x 1 thread): rounds of 4 s left the ranks as idle as
/// rounds of 1 s (2.4 % and 2.3 % of the time waiting for the slowest): the wait is the ranks' imbalance, not the number of rounds.
constexpr double kRoundSeconds = 1.0;

/// The numbers each rank reports at a round's end: its compute seconds, whether it was asked to stop, whether it failed.
constexpr std::size_t kReport = 3;

std::string partName(const std::string& manifest, std::uint64_t blocks, int rank) {
  return std::filesystem::path(manifest).filename().string() + ".b" + std::to_string(blocks) + ".r" +
         std::to_string(rank) + ".json";
}

/// Removes what an aborted checkpoint left beside `manifest` (its parts, and the temporaries of parts being
/// written when a rank was killed) except the parts in `keep`.  Rank 0 only, holding the manifest's lock.
void removeStaleParts(const std::string& manifest, const std::vector<std::string>& keep) {
  const std::filesystem::path path(manifest);
  const std::filesystem::path folder = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  const std::string prefix = path.filename().string() + ".b";
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    const bool part = name.starts_with(prefix) && name.ends_with(".json");
    const bool temporary = name.starts_with("." + prefix);
    if ((part || temporary) && std::find(keep.begin(), keep.end(), name) == keep.end()) {
      std::error_code ignored;
      std::filesystem::remove(entry.path(), ignored);
    }
  }
}

/// The whole state to resume: a manifest of parts or a plain run file (e.g. archipelago-cli run's checkpoint).
TrappingState loadResume(const std::string& path) {
  // A manifest is small; a larger file can only be a run file, read with its memory check (io::loadJsonFile).
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxManifestBytes) return loadRunFile(path);
  const std::string text = io::readRegularFile(path, kMaxRunFileBytes);
  if (looksLikeRunManifest(text)) return loadRunManifest(path);
  try {
    return parseRunFile(text);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

/// A collective checkpoint at the ranks' common blocksDone: each rank writes its part, then (when all did)
/// rank 0 the manifest, then removes the previous checkpoint's parts.  A failure warns and the run goes on
/// (the previous checkpoint stays whole).  Returns whether the new checkpoint was written.
bool writeCollectiveCheckpoint(const World& w, const TrappingState& s, const std::string& manifest,
                     std::vector<std::string>& previousParts, bool breakLine) {
  const std::filesystem::path folder = std::filesystem::path(manifest).parent_path();
  const std::string mine = partName(manifest, s.blocksDone, w.rank);
  std::string message;
  bool ok = true;
  try {
    saveRunFile(folder / mine, s);
  } catch (const std::exception& e) {
    ok = false;
    message = e.what();
  }
  try {
    agree(w, ok, message);
  } catch (const std::exception& e) {
    if (w.rank == 0)
      std::fprintf(stderr, "%sWARNING: checkpoint not written: %s; the run goes on\n", breakLine ? "\n" : "", e.what());
    return false;
  }
  int written = 1;
  if (w.rank == 0) {
    RunManifest m;
    m.blocksDone = s.blocksDone;
    for (int r = 0; r < w.size; ++r) {
      const auto [b, e] = rankRange(s.params.M, r, w.size);
      m.parts.push_back({partName(manifest, s.blocksDone, r), b, e});
    }
    try {
      io::writeFileAtomically(manifest, runManifestText(m));
      std::vector<std::string> now;
      for (const auto& p : m.parts) now.push_back(p.file);
      for (const std::string& old : previousParts)
        if (std::find(now.begin(), now.end(), old) == now.end()) {
          std::error_code ignored;
          std::filesystem::remove(folder / old, ignored);
        }
      previousParts = now;
    } catch (const std::exception& e) {
      written = 0;
      std::fprintf(stderr, "%sWARNING: checkpoint manifest not written: %s; the run goes on\n", breakLine ? "\n" : "",
                   e.what());
    }
  }
  MPI_Bcast(&written, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return written == 1;
}

/// What every rank checks alike (the same arguments): one error, printed by rank 0.  Returns the run to do with its
/// spec resolved (a new run), or nothing when --print-spec printed it.
std::optional<cli::RunOptions> checkedRun(const World& w, const cli::RunOptions& o,
                                          const std::vector<std::string>& explicitParameters, const CLI::App& cmd) {
  if (!o.seeds.empty()) throw std::invalid_argument("archipelago-mpi runs one seed: give --seed (or run one job per seed)");
  if (!o.orbits.empty())
    throw std::invalid_argument("archipelago-mpi partitions the orbits over its ranks itself: do not give --orbits");
  if (!o.resume.empty() && !explicitParameters.empty())
    throw std::invalid_argument("--resume takes the parameters from the run file; do not also give " +
                                explicitParameters.front());
  if (auto e = threadsError(o.threads)) throw std::invalid_argument("--" + *e);  // --resume skips the spec's check
  if (auto e = checkpointIntervalError("--checkpoint-interval", o.checkpointSeconds)) throw std::invalid_argument(*e);
  cli::RunOptions run = o;
  if (o.resume.empty()) {
    const RunSpec spec = cli::resolveSpec(o, cmd);
    if (o.printSpec) {
      if (w.rank == 0) std::fputs(runSpecJson(spec).c_str(), stdout);
      return std::nullopt;
    }
    run.params = spec.parameters;
    run.threads = spec.threads;
    run.kernel = spec.kernel == "auto" ? std::string() : spec.kernel;
  }
  return run;
}

/// This rank's orbits: a new run's share, or its share of the checkpoint to resume (every rank reads the whole
/// file on a shared file system and keeps its own orbits; rank 0 carries the statistics so far).  Rank 0 also
/// learns the parts of the manifest written last.
TrappingState rankState(const World& w, const cli::RunOptions& run, const std::string& manifest,
                        std::vector<std::string>& previousParts) {
  const bool root = w.rank == 0;
  const auto ranksFit = [&w](std::uint64_t M) {
    if (auto e = orbitPartsError(static_cast<std::uint64_t>(w.size), M, "ranks")) throw std::invalid_argument(*e);
  };
  if (run.resume.empty()) {
    ranksFit(run.params.M);
    if (auto e = memoryError(run.params, run.threads)) throw std::runtime_error(*e);
    const auto [b, e] = rankRange(run.params.M, w.rank, w.size);
    return startTrapping(run.params, b, e);
  }
  TrappingState whole = loadResume(run.resume);
  if (whole.finished())
    throw std::invalid_argument(run.resume + " is already finished (" + std::to_string(whole.blocksDone) +
                                " of T blocks)");
  ranksFit(whole.params.M);
  const auto [b, e] = rankRange(whole.params.M, w.rank, w.size);
  TrappingState state = sliceRun(whole, b, e, root);
  std::error_code ec;
  if (root && run.resume == manifest && std::filesystem::file_size(run.resume, ec) <= kMaxManifestBytes && !ec) {
    const std::string text = io::readRegularFile(run.resume, kMaxManifestBytes);
    if (looksLikeRunManifest(text))
      for (const auto& p : parseRunManifest(text, run.resume).parts) previousParts.push_back(p.file);
  }
  return state;
}

/// Rank 0's account of the rounds: what it decides and what it reports at the end.
struct Rounds {
  std::uint64_t blocks = 16;          ///< the next round's length
  std::uint64_t count = 0;            ///< rounds done
  double idleSeconds = 0;             ///< the ranks' waits for the slowest at the rounds' ends, averaged over ranks
  std::vector<double> seconds, busy;  ///< each rank's compute seconds: this round's, and summed
  Clock::time_point sessionStart = Clock::now(), lastCheckpoint = sessionStart, lastLine = sessionStart - std::chrono::hours(1);
  std::uint64_t startBlocks = 0;
};

/// The progress line of rank 0 (a bar on a terminal; on a pipe or file, a line every 10 s).
void drawRoundProgress(const cli::RunOptions& o, const TrappingState& state, Rounds& r, const World& w,
                       const KernelInfo& kernel, bool tty) {
  const auto now = Clock::now();
  if (o.quiet || (!tty && std::chrono::duration<double>(now - r.lastLine).count() < 10)) return;
  const std::uint64_t T = state.params.T;
  const double stepsPerBlock = static_cast<double>(state.params.M) * state.params.q;
  const double session = std::chrono::duration<double>(now - r.sessionStart).count();
  const double rate = session > 0 ? static_cast<double>(state.blocksDone - r.startBlocks) * stepsPerBlock / session : 0;
  TrappingProgress p;
  p.blocksDone = state.blocksDone;
  p.blocksTotal = T;
  p.fraction = static_cast<double>(state.blocksDone) / static_cast<double>(T);
  p.stepsPerSecond = rate;
  p.etaSeconds = rate > 0 ? static_cast<double>(T - state.blocksDone) * stepsPerBlock / rate : -1;
  const auto slowest = std::max_element(r.seconds.begin(), r.seconds.end());
  const double fastest = std::max(1e-9, *std::min_element(r.seconds.begin(), r.seconds.end()));
  cli::drawProgress(p, std::string(kernel.name) + ", " + std::to_string(w.size) + " ranks, slowest rank " +
                           std::to_string(slowest - r.seconds.begin()) + " " +
                           std::to_string(static_cast<int>(100 * *slowest / fastest - 100 + 0.5)) + "% behind");
  if (!tty) std::fputc('\n', stderr);
  r.lastLine = now;
}

/// Rank 0 decides for all from the gathered reports ({compute seconds, asked to stop, failed} per rank): the next
/// round's length, a checkpoint, a stop, a failure — {blocks, checkpoint, stop, failed}.
std::array<std::uint64_t, 4> decideRound(const std::vector<double>& reports, const cli::RunOptions& o,
                                         const TrappingState& state, Rounds& r, const World& w) {
  bool stopAny = false;
  bool failedAny = false;
  for (int k = 0; k < w.size; ++k) {
    r.seconds[static_cast<std::size_t>(k)] = reports[kReport * static_cast<std::size_t>(k)];
    stopAny = stopAny || reports[kReport * static_cast<std::size_t>(k) + 1] != 0;
    failedAny = failedAny || reports[kReport * static_cast<std::size_t>(k) + 2] != 0;
  }
  const double slowest = *std::max_element(r.seconds.begin(), r.seconds.end());
  for (std::size_t k = 0; k < r.seconds.size(); ++k) {
    r.idleSeconds += (slowest - r.seconds[k]) / static_cast<double>(w.size);
    r.busy[k] += r.seconds[k];
  }
  ++r.count;
  std::array<std::uint64_t, 4> decision{r.blocks, 0, 0, failedAny ? 1U : 0U};
  const double perBlock = slowest / static_cast<double>(r.blocks);
  if (perBlock > 0)
    decision[0] = static_cast<std::uint64_t>(std::clamp(kRoundSeconds / perBlock, 1.0, 4.0 * static_cast<double>(r.blocks)));
  else decision[0] = 4 * r.blocks;
  if (o.maxChunkBlocks != 0) decision[0] = std::min(decision[0], o.maxChunkBlocks);
  decision[2] = stopAny ? 1 : 0;
  decision[1] = state.blocksDone < state.params.T &&
                (decision[2] != 0 ||
                 std::chrono::duration<double>(Clock::now() - r.lastCheckpoint).count() >= o.checkpointSeconds);
  return decision;
}

/// Rounds to common block counts until the run ends or a rank is interrupted (then a checkpoint is written): each
/// rank computes its round, one gather of two numbers a rank and one broadcast of rank 0's decision follow, both
/// waited for without spinning (a rank that finished its round first sleeps, leaving its core to the others).
/// Returns whether the run was interrupted.
bool runRounds(const World& w, const cli::RunOptions& o, const cli::RunOptions& run, TrappingState& state,
               Rounds& r, const std::string& manifest, std::vector<std::string>& previousParts) {
  const bool root = w.rank == 0;
  const KernelInfo& kernel = selectKernel(run.kernel);
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  TrappingRunOptions options;
  options.kernel = &kernel;
  options.threads = run.threads;
  options.maxChunkBlocks = o.maxChunkBlocks;
  const std::uint64_t T = state.params.T;
  std::vector<double> reports(root ? kReport * static_cast<std::size_t>(w.size) : kReport);
  while (state.blocksDone < T) {
    options.untilBlocks = std::min(T, state.blocksDone + r.blocks);
    const auto t0 = Clock::now();
    std::string error;  // an error of this rank alone (its memory): told to every rank at the round's end
    try {
      state = runTrapping(std::move(state), options);
    } catch (const std::exception& e) {
      error = e.what();
    }
    const double mine[kReport] = {std::chrono::duration<double>(Clock::now() - t0).count(),
                                  cli::interruptRequested() ? 1.0 : 0.0, error.empty() ? 0.0 : 1.0};
    MPI_Request request = MPI_REQUEST_NULL;
    MPI_Igather(mine, kReport, MPI_DOUBLE, reports.data(), kReport, MPI_DOUBLE, 0, MPI_COMM_WORLD, &request);
    waitWithoutSpinning(request);
    std::array<std::uint64_t, 4> decision{r.blocks, 0, 0, 0};  // blocks, checkpoint, stop, failed
    if (root) {
      decision = decideRound(reports, o, state, r, w);
      drawRoundProgress(o, state, r, w, kernel, tty);
    }
    MPI_Ibcast(decision.data(), 4, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
    waitWithoutSpinning(request);
    if (decision[3] != 0) agree(w, error.empty(), error);  // throws on every rank: one ERROR, by rank 0
    r.blocks = decision[0];
    if (decision[1] != 0 && writeCollectiveCheckpoint(w, state, manifest, previousParts, root && tty && !o.quiet))
      r.lastCheckpoint = Clock::now();
    if (decision[2] != 0 && state.blocksDone < T) return true;
  }
  return false;
}

/// Rank 0's end: the other ranks' states gathered and merged, the run file written (rescued when that fails), the
/// superseded checkpoint removed, the summary printed; the other ranks send their state.  Run together(): rank 0's
/// error is every rank's.
void gatherAndWrite(const World& w, const cli::RunOptions& o, TrappingState state, const Rounds& r,
                    const std::string& manifest, const std::vector<std::string>& previousParts,
                    double computeSeconds, double sessionSteps) {
  if (w.rank != 0) {
    sendText(runFileText(state), 0);
    return;
  }
  std::vector<RunPart> parts;
  parts.push_back({"rank 0", std::move(state)});
  for (int k = 1; k < w.size; ++k) parts.push_back({"rank " + std::to_string(k), parseRunFile(receiveText(k))});
  const TrappingState merged = mergeRunParts(std::move(parts));
  cli::saveRunFileOrSayWhere(o.out, merged, LastCheckpoint{previousParts.empty() ? std::string() : manifest, 0});
  // The run file holds everything now: the checkpoint's parts and manifest are superseded.
  const std::filesystem::path folder = std::filesystem::path(manifest).parent_path();
  std::error_code ignored;
  for (const std::string& p : previousParts) std::filesystem::remove(folder / p, ignored);
  if (!previousParts.empty()) std::filesystem::remove(manifest, ignored);
  if (o.quiet) return;
  const TrappingHistogram total = merged.total();
  const std::uint64_t longest = merged.longest.items().empty() ? 0 : merged.longest.items().front().length;
  const auto busiest = std::max_element(r.busy.begin(), r.busy.end());
  const auto idlest = std::min_element(r.busy.begin(), r.busy.end());
  std::fprintf(stderr,
               "done: %llu segments, longest %llu steps, %.3g steps on %d ranks in %.1f s; wrote %s\n"
               "compute: %.4g steps in %.3f s = %.4g steps/s (rank 0's MPI_Wtime, setup and final write "
               "excluded); %llu rounds, the ranks idle %.2f%% of it waiting for the slowest; "
               "busiest rank %d %.3f s, least busy rank %d %.3f s\n",
               static_cast<unsigned long long>(total.segments()),
               static_cast<unsigned long long>(longest * merged.params.q), merged.stepsDone(), w.size,
               std::chrono::duration<double>(Clock::now() - r.sessionStart).count(), o.out.c_str(), sessionSteps,
               computeSeconds, computeSeconds > 0 ? sessionSteps / computeSeconds : 0.0,
               static_cast<unsigned long long>(r.count), computeSeconds > 0 ? 100 * r.idleSeconds / computeSeconds : 0.0,
               static_cast<int>(busiest - r.busy.begin()), *busiest, static_cast<int>(idlest - r.busy.begin()), *idlest);
}

}  // namespace

int mpiRun(const cli::RunOptions& o, const std::vector<std::string>& explicitParameters, const CLI::App& cmd) {
  const World w = world();
  MpiRanks ranks;
  const bool root = w.rank == 0;
  const std::optional<cli::RunOptions> run = checkedRun(w, o, explicitParameters, cmd);
  if (!run) return 0;  // --print-spec
  const std::string manifest = o.checkpoint.empty() ? o.out + ".checkpoint" : o.checkpoint;
  if (manifest == o.out) throw std::invalid_argument("--checkpoint must differ from --out (it is a manifest of parts)");
  // The files: checked and locked by rank 0, every rank told the outcome.
  std::vector<io::FileLock> locks;
  together(ranks, [&] {
    if (!root) return;
    io::checkWritableTarget(o.out);
    io::checkWritableTarget(manifest);
    locks = cli::lockRunFiles(o.out, manifest, o.resume);
  });
  TrappingState state;
  std::vector<std::string> previousParts;  // rank 0: the parts of the manifest written last
  together(ranks, [&] { state = rankState(w, *run, manifest, previousParts); });  // errors found alike on every rank
  if (root) removeStaleParts(manifest, previousParts);
  if (root) cli::warnIfBoxCutsIsland(state.params);  // as archipelago-cli run says it (issue 39), once
  cli::installInterruptHandlers();
  // The compute time (rank 0's report): from here, every rank set up, to the end of the last round, before the
  // gather and the final write; mpirun's start, MPI_Init and the reading of files are outside it.
  MPI_Barrier(MPI_COMM_WORLD);
  const double computeStart = MPI_Wtime();
  Rounds r;
  r.startBlocks = state.blocksDone;
  r.blocks = o.maxChunkBlocks != 0 ? std::min<std::uint64_t>(o.maxChunkBlocks, 16) : 16;
  r.seconds.assign(root ? static_cast<std::size_t>(w.size) : 1, 0.0);
  r.busy.assign(r.seconds.size(), 0.0);
  const bool interrupted = runRounds(w, o, *run, state, r, manifest, previousParts);
  const double computeSeconds = MPI_Wtime() - computeStart;
  const double sessionSteps = static_cast<double>(state.blocksDone - r.startBlocks) *
                              static_cast<double>(state.params.M) * state.params.q;
  if (root && !o.quiet && ::isatty(STDERR_FILENO) != 0) std::fputc('\n', stderr);
  if (interrupted) {
    if (root)
      std::fprintf(stderr, "interrupted: checkpoint written to %s (resume with --resume %s, on any number of ranks)\n",
                   manifest.c_str(), manifest.c_str());
    return 130;
  }
  together(ranks, [&] {
    gatherAndWrite(w, o, std::move(state), r, manifest, previousParts, computeSeconds, sessionSteps);
  });
  return 0;
}

}  // namespace archipelago::mpi
