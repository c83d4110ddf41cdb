#include "MergeCommand.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "RunSession.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/runfile/RunFileMerge.hpp"
#include "core/tail/TailFile.hpp"

namespace archipelago::cli {

namespace {
struct MergeOptions {
  std::vector<std::string> parts;
  std::string out;
  bool quiet = false;
};

int mergeCommand(const MergeOptions& o) {
  std::vector<io::CommandFile> files{{"--out", o.out, io::FileUse::Output}};
  for (const std::string& part : o.parts) files.push_back({"part", part, io::FileUse::Input});
  io::checkCommandFiles(files);  // before reading the parts: --out is none of them, no part is given twice
  const std::vector<io::FileLock> locks = lockRunFiles(o.out, o.out, "");
  if (isTailFile(o.parts.front())) {
    // The slices of a distributed sampler run (tail --slice, archipelago-mpi tail).
    std::vector<TailState> slices;
    for (const std::string& path : o.parts) slices.push_back(loadTailFile(path));
    const TailState merged = mergeTailSlices(std::move(slices));
    saveTailFile(o.out, merged);
    if (!o.quiet)
      std::fprintf(stderr, "merged %zu slices of the tail sampler: replicas [0, %u), %llu steps; wrote %s\n",
                   o.parts.size(), merged.request.replicas, static_cast<unsigned long long>(merged.steps),
                   o.out.c_str());
    return 0;
  }
  std::vector<RunPart> parts;
  parts.reserve(o.parts.size());
  for (const std::string& path : o.parts) parts.push_back({path, loadRunFile(path)});  // a modified file: its path
  const TrappingState merged = mergeRunParts(std::move(parts));
  saveRunFile(o.out, merged);
  if (!o.quiet)
    std::fprintf(stderr, "merged %zu parts: orbits [0, %llu), %llu of %llu blocks; wrote %s\n", o.parts.size(),
                 static_cast<unsigned long long>(merged.orbitEnd), static_cast<unsigned long long>(merged.blocksDone),
                 static_cast<unsigned long long>(merged.params.T), o.out.c_str());
  return 0;
}
}  // namespace

void addMergeCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "merge the run files of separate orbit ranges of one run (run --orbits BEGIN:END) into one, or the "
               "tail files of the slices of one sampler run (tail --slice I/N)");
  cmd->add_option("parts", o->parts, "the run files of the parts, in any order; together orbits [0, M) (or the tail "
                                     "files of the slices, together replicas [0, R))")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "the merged run file")->required();
  cmd->add_flag("--quiet", o->quiet, "no summary");
  cmd->callback([o, &status] { status = mergeCommand(*o); });
}

}  // namespace archipelago::cli
