#include "RunSession.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <variant>

#include "CliCommon.hpp"
#include "core/atlas/BoxIslandCheck.hpp"
#include "core/runfile/RunFile.hpp"

namespace archipelago::cli {

namespace {
volatile std::sig_atomic_t gInterrupted = 0;
int gWakeFd = -1;  // the write end of the self-pipe that wakes the thread turning a signal into the program's stop
extern "C" void onInterrupt(int) {
  gInterrupted = 1;
  if (gWakeFd >= 0) {
    const char byte = 1;
    [[maybe_unused]] const ssize_t n = ::write(gWakeFd, &byte, 1);  // async-signal-safe
  }
}
std::stop_source& interruptSource() {
  static std::stop_source source;
  return source;
}
}  // namespace

void addSpecOptions(CLI::App& cmd, SpecOptions& o, std::initializer_list<std::string_view> without) {
  cmd.add_option("--preset", o.preset, "start from a preset of the paper (archipelago-cli presets lists them)");
  cmd.add_option("--spec", o.specFile, "start from a run spec file (JSON; run --print-spec writes one)");
  // One option per parameter of the run, from core's table (TrappingParameters.hpp): name, meaning, range.
  // Given explicitly, a parameter overrides the preset's or the spec file's.
  const RunSpec defaults;
  for (const ParameterRule& rule : parameterRules()) {
    if (std::find(without.begin(), without.end(), rule.key) != without.end()) continue;
    const std::string key(rule.key);
    const std::string help = std::string(rule.meaning) + "; " + std::string(rule.range);
    const ParameterValue value = parameterValue(defaults.parameters, key);
    const std::string names = "--" + key + (key == "longestKept" ? ",--longest" : "");  // --longest: the old name
    if (rule.integer) addNumberOption(cmd, names, o.integers[key] = std::get<std::uint64_t>(value), help);
    else addNumberOption(cmd, names, o.reals[key] = std::get<double>(value), help);
  }
}

std::vector<std::string> givenSpecOptions(const CLI::App& cmd) {
  std::vector<std::string> given;
  for (const ParameterRule& rule : parameterRules()) {
    const std::string name = "--" + std::string(rule.key);
    const CLI::Option* option = cmd.get_option_no_throw(name);
    if (option != nullptr && option->count() > 0) given.push_back(name);
  }
  for (const char* name : {"--preset", "--spec"})
    if (cmd.count(name) > 0) given.emplace_back(name);
  return given;
}

RunSpec resolveSpec(const SpecOptions& o, const CLI::App& cmd) {
  if (!o.preset.empty() && !o.specFile.empty()) throw std::invalid_argument("give --preset or --spec, not both");
  // An empty --preset= or --spec= is a mistake, never a silent fall back to the defaults.
  if (cmd.count("--preset") > 0 && o.preset.empty())
    throw std::invalid_argument("--preset is empty (archipelago-cli presets lists the presets)");
  if (cmd.count("--spec") > 0 && o.specFile.empty()) throw std::invalid_argument("--spec is empty: give a spec file");
  RunSpec spec;
  if (!o.preset.empty()) {
    const Preset* preset = findPreset(o.preset);
    if (!preset) {
      std::string ids;
      for (const Preset& p : presets()) ids += (ids.empty() ? "" : ", ") + p.id;
      throw std::invalid_argument("--preset " + o.preset + " is not a preset (presets: " + ids + ")");
    }
    spec = preset->spec;
  } else if (!o.specFile.empty()) {
    spec = loadRunSpec(o.specFile);
  }
  for (const ParameterRule& rule : parameterRules()) {
    const std::string key(rule.key);
    const bool known = rule.integer ? o.integers.count(key) > 0 : o.reals.count(key) > 0;
    if (!known || cmd.count("--" + key) == 0) continue;
    if (rule.integer) setParameterValue(spec.parameters, key, o.integers.at(key));
    else setParameterValue(spec.parameters, key, o.reals.at(key));
  }
  if (cmd.count("--threads") > 0) spec.threads = o.threads;
  if (cmd.count("--kernel") > 0) spec.kernel = o.kernel.empty() ? "auto" : o.kernel;
  if (auto e = validationError(spec)) throw std::invalid_argument(*e);
  return spec;
}

void warnIfBoxCutsIsland(const TrappingParameters& p) {
  if (const BoxIslandCheck c = checkBoxAgainstIsland(p.map, p.Xr); c.cuts())
    std::fprintf(stderr, "WARNING: %s\n", c.warning.c_str());
}

std::vector<io::FileLock> lockRunFiles(const std::string& out, const std::string& checkpoint, const std::string& resume) {
  return lockJobFiles(out, checkpoint, resume);
}

void installInterruptHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    // A signal handler may not request a stop (stop_source is not async-signal-safe): it writes a byte that wakes
    // a thread blocked on the pipe, and that thread requests it.  No polling, no fixed wait.
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("cannot install the Ctrl-C handler: no pipe");
    gWakeFd = fds[1];
    std::thread([readEnd = fds[0]] {
      char byte = 0;
      while (::read(readEnd, &byte, 1) < 0 && errno == EINTR) {
      }
      interruptSource().request_stop();
    }).detach();
    std::signal(SIGINT, onInterrupt);
    std::signal(SIGTERM, onInterrupt);
  });
}

std::stop_token interruptToken() {
  installInterruptHandlers();
  return interruptSource().get_token();
}

bool interruptRequested() noexcept { return gInterrupted != 0; }

std::string clockText(double seconds) {
  if (!(seconds >= 0) || seconds > 1e8) return "--:--:--";
  const auto s = static_cast<long long>(seconds + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  return buf;
}

std::string howToResume(const LastCheckpoint& last) {
  return last.path.empty() ? std::string() : ": resume with --resume " + last.path;
}

void saveRunFileOrSayWhere(const std::string& path, const TrappingState& state, const LastCheckpoint& last) {
  archipelago::saveRunFileOrSayWhere(path, state, last, howToResume(last));
}

}  // namespace archipelago::cli
