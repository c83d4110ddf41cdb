#include "core/tail/TailPlan.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/atlas/BoxIslandCheck.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"
#include "core/runfile/CheckpointedRun.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/tail/BruteForceSurvival.hpp"
#include "core/tail/TailFile.hpp"

namespace archipelago {

CloneRule parseCloneRule(const std::string& text, const std::string& option) {
  const auto rule = cloneRuleByName(text);
  if (!rule) throw std::invalid_argument(option + " '" + io::shortText(text) + "' must be perturb or metropolis");
  return *rule;
}

ReplicaRange parseReplicaSlice(const std::string& option, const std::string& text, std::uint32_t replicas) {
  const std::string rule = "I/N, whole numbers with I < N <= R = " + std::to_string(replicas) + " (slice I of N)";
  const std::vector<std::uint32_t> v = io::parseNumbers<std::uint32_t>(option, text, '/', 2, rule);
  if (!(v[0] < v[1] && v[1] <= replicas))
    throw std::invalid_argument(option + " '" + io::shortText(text) + "' must be " + rule);
  return replicaSlice(replicas, v[0], v[1]);
}

std::string TailPlanOptions::nameOf(std::string_view role) const {
  return optionName ? optionName(role) : std::string(role);
}

TailPlan planTail(const TailPlanOptions& o) {
  const auto name = [&o](std::string_view role) { return o.nameOf(role); };
  const std::string& resume = o.resumeFile.empty() ? o.resume : o.resumeFile;
  std::optional<ReplicaRange> slice = o.slice;
  if (o.sliceText) {  // given empty is an error too, not the whole run (issue 36)
    if (!o.resume.empty())
      throw std::invalid_argument(name("resume") + " takes the slice from the tail file; do not also give " +
                                  name("slice"));
    slice = parseReplicaSlice(name("slice"), *o.sliceText, o.request.replicas);
  }
  if (!o.resume.empty()) {
    if (!o.givenSpec.empty())
      throw std::invalid_argument(name("resume") + " takes the spec from the tail file; do not also give " +
                                  o.givenSpec.front());
    if (!o.givenSampler.empty())
      throw std::invalid_argument(name("resume") + " takes the sampler's settings from the tail file; do not also give " +
                                  o.givenSampler.front());
    if (o.printLevels)
      throw std::invalid_argument(name("print-levels") + " prints a new run's levels; do not give " + name("resume"));
  }
  if (auto e = threadsError(o.threads)) throw std::invalid_argument(*e);  // the one table's rule and wording
  if (auto e = checkpointIntervalError(name("checkpoint-interval"), o.checkpointSeconds)) throw std::invalid_argument(*e);

  TailPlan plan;
  plan.threads = o.threads;
  if (o.resume.empty()) {
    if (!o.spec) throw std::invalid_argument("a new tail run needs its spec");
    const RunSpec spec = o.spec();
    if (o.warning) {
      if (const BoxIslandCheck c = checkBoxAgainstIsland(spec.parameters.map, spec.parameters.Xr); c.cuts())
        o.warning(c.warning);
    }
    TailRequest request = o.request;
    request.run = spec.parameters;
    plan.threads = spec.threads;
    plan.kernel = spec.kernel == "auto" ? std::string() : spec.kernel;
    request.clones = parseCloneRule(o.clones, name("clones"));
    if (auto e = tailRequestError(request)) throw std::invalid_argument(*e);
    plan.state = slice ? startTailSlice(request, *slice) : startTail(request);
    if (o.printLevels) {
      plan.printLevelsOnly = true;
      return plan;
    }
  }
  const std::string checkpoint = o.checkpoint.empty() ? o.out : o.checkpoint;
  if (!o.compareCsv.empty() && o.compare.empty())
    throw std::invalid_argument(name("compare-csv") + " needs " + name("compare") + " RUN.json");
  std::vector<io::CommandFile> files{{name("out"), o.out, io::FileUse::SavedState},
                                     {name("checkpoint"), checkpoint, io::FileUse::SavedState},
                                     {name("resume"), resume, io::FileUse::ResumedState},
                                     {name("csv"), o.csv, io::FileUse::Output},
                                     {name("compare-csv"), o.compareCsv, io::FileUse::Output},
                                     {name("spec"), o.specFile, io::FileUse::Input}};
  for (const std::string& run : o.compare) files.push_back({name("compare"), run, io::FileUse::Input});
  io::checkCommandFiles(files);  // no output over another or over an input; a run compared once
  // A state path that holds a file of another format (a run file, an atlas, notes) is refused as an input of the wrong
  // format is: the tail would write its state over it (issue 54, item 8: `--checkpoint r.json` replaced a run file).
  // An empty file holds nothing to lose, and a tail file is the state this command writes.
  for (const auto& [option, path] : {std::pair<std::string, const std::string&>{name("out"), o.out},
                                     std::pair<std::string, const std::string&>{name("checkpoint"), checkpoint}}) {
    std::error_code ec;
    if (path.empty() || !std::filesystem::is_regular_file(path, ec) || std::filesystem::file_size(path, ec) == 0 || ec)
      continue;
    if (!isTailFile(path))
      throw std::invalid_argument(option + " " + path +
                                  " holds a file that is not a tail file: the tail does not write its state over it "
                                  "(name another file, or remove it)");
  }
  if (!resume.empty()) {
    plan.state = loadTailFile(resume);
    if (plan.state.finished() && o.resumeFile.empty()) throw std::invalid_argument(resume + " is already finished");
  }
  // The runs to compare with, read and checked before any work.
  for (const std::string& path : o.compare) {
    plan.runs.push_back(loadRunFile(path));
    if (auto e = tailRunMismatch(plan.state.request, plan.runs.back()))
      throw std::invalid_argument(path + " is not a run of the sampler's process: " + *e);
  }
  if (!plan.runs.empty()) (void)bruteForceSurvival(plan.runs, plan.state.levels);  // throws when the runs do not pool
  return plan;
}

}  // namespace archipelago
