#include "ReplayCommand.hpp"

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "CliCommon.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/periodic/SegmentAnalysis.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/trapping/LongestSegments.hpp"

namespace archipelago::cli {

namespace {
struct ReplayOptions {
  std::string runFile;
  std::size_t segment = 0;
  std::string out;
  std::uint64_t stride = 1;
  bool identify = false;
};

int replayCommand(const ReplayOptions& o) {
  const TrappingState state = loadRunFile(o.runFile);
  const auto& items = state.longest.items();
  if (auto e = longestRankError("--segment", o.segment, items.size())) throw std::invalid_argument(*e);
  if (auto e = strideError(o.stride)) throw std::invalid_argument(*e);
  io::checkCommandFiles({{"run", o.runFile, io::FileUse::Input}, {"--out", o.out, io::FileUse::Output}});  // before the replay
  const SegmentRecord& rec = items[o.segment];
  // Streamed and atomic; bounded by the record: a segment that does not end where the run recorded it is a
  // "replay mismatch" error and --out is left untouched (issue #12, finding 5).
  (void)writeSegmentCsv(o.out, state.params, rec, o.stride);
  std::fprintf(stderr, "segment %zu: orbit %llu, %llu blocks (%llu steps), replayed bit for bit to %s\n", o.segment,
               static_cast<unsigned long long>(rec.orbit), static_cast<unsigned long long>(rec.length),
               static_cast<unsigned long long>(rec.length * state.params.q), o.out.c_str());
  if (o.identify) {
    // The GUI's path (long-segment table): the first kChainIdentificationPoints consecutive points at most.  The
    // segment iterates N⁻¹ (time reversed); the chain it sticks to is the same for Q.
    const SegmentChain found = *identifySegmentChain(state.params, rec);
    const IslandChain& chain = found.chain;
    std::printf("# chain_period: %d\n# hierarchy:", chain.period);
    for (int level : chain.hierarchy) std::printf(" %d", level);
    std::printf("\n# member: %.12Lg,%.12Lg\n", chain.member.x, chain.member.y);
    std::printf("# points_used: %llu (the first consecutive points of the segment)\n",
                static_cast<unsigned long long>(found.points));
    if (chain.centre) {
      std::printf("# centre_orbit: period %d at %.12Lg,%.12Lg, residue %.9Lg (%s)\n", chain.centre->period,
                  chain.centre->points.front().x, chain.centre->points.front().y, chain.centre->residue,
                  chain.centre->classification().description());
    }
  }
  return 0;
}
}  // namespace

void addReplayCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<ReplayOptions>();
  CLI::App* cmd = app.add_subcommand("replay", "replay a recorded long segment exactly; CSV of its points");
  cmd->add_option("run", o->runFile, "run file")->required();
  addNumberOption(*cmd, "--segment", o->segment, "rank of the segment (0: the longest)");
  cmd->add_option("--out", o->out, "CSV file to write")->required();
  addNumberOption(*cmd, "--stride", o->stride, "write every stride-th step");
  cmd->add_flag("--identify", o->identify, "identify the island chain the segment sticks to (period, centre orbit)");
  cmd->callback([o, &status] { status = replayCommand(*o); });
}

}  // namespace archipelago::cli
