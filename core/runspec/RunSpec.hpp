#pragma once
/// \file RunSpec.hpp
/// \brief The run specification: everything that defines a trapping run to start, and its one JSON codec.
///
/// A RunSpec holds the trapping parameters (the map K, xmin, xmax; the randomizing zone Xr; q, T, M; the
/// seed; the subsets; how many longest segments keep their start state: Karney 1983, §3 and appendix B) and
/// how to compute them (the kernel and the thread count, which never change a result).  Every surface reads
/// and writes parameters through this file: run files (their "parameters" object), presets, portrait and b₂
/// sidecars (their map), the GUI's saved settings, and the CLI's `run --spec` / `--preset` / `--print-spec`.
///
/// The JSON form (format "archipelago-spec", version 1):
///
///     {"format": "archipelago-spec", "version": 1,
///      "name": "…", "description": "…",                      (optional: presets and saved specs)
///      "parameters": {"K": 0.1, "xmin": -0.8, "xmax": 0.5, "Xr": 0.02, "q": 16, "T": 1000000,
///                     "M": 64, "seed": 1, "subsets": 16, "longestKept": 100},
///      "kernel": "auto", "threads": 0, "companion": 0.1}              ("companion": optional, q > 1 only)
///
/// Reals are written with the shortest decimal form that reads back to the same double; integers as JSON
/// integers (exact to 2^64).  The keys and the documented range of each parameter are TrappingParameters'
/// one table (parameterRules()).  When read, a spec may leave out any parameter: it then takes the default of
/// TrappingParameters (the paper's K = 0.1 box, §5), and runSpecJson() of the result shows every value.  A
/// run file's parameters must be complete.  Unknown keys, a value of the wrong type, a fractional or
/// out-of-range integer and a repeated key are errors that name the key: a typo never falls back silently
/// to a default.

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/runspec/InputRules.hpp"  // kMaxThreads, threadsError
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago {

inline constexpr const char* kRunSpecFormatName = "archipelago-spec";
inline constexpr int kRunSpecFormatVersion = 1;

/// A run to start.  Defaults: the paper's K = 0.1 case (TrappingParameters), the fastest kernel, all cores.
struct RunSpec {
  TrappingParameters parameters;
  std::string kernel = "auto";  ///< "auto" or a kernel name (kernels/KernelDispatch.hpp); chosen at the edges
  int threads = 0;              ///< OpenMP threads, 0 … kMaxThreads; 0: one per core
  /// A run of q > 1 may carry a q = 1 companion for its short times (issue #26): the fraction of the run's steps
  /// it costs, in (0, 1]; 0: none.  companionParameters(parameters, companion) are its parameters.
  double companion = 0;
  std::string name;             ///< a short title (presets); may be empty
  std::string description;      ///< one paragraph (presets); may be empty

  friend bool operator==(const RunSpec&, const RunSpec&) = default;
};


/// The first violated rule of the spec (the parameters' rules, the kernel's name, the thread count), naming
/// the field, or nothing when valid.  The kernel is checked by name only: whether this CPU can run it is
/// decided when the run starts (selectKernel).
[[nodiscard]] std::optional<std::string> validationError(const RunSpec& spec);

/// The spec as JSON text (every field, two-space indent, a final newline).
[[nodiscard]] std::string runSpecJson(const RunSpec& spec);

/// Reads a spec from JSON text.  Throws io::BadFile with one line naming the key for bad content
/// (not JSON, wrong format, unknown or repeated key, wrong type, fractional or out-of-range integer) and for a
/// spec that breaks a rule of validationError().
[[nodiscard]] RunSpec parseRunSpec(std::string_view text);

/// Reads a spec file.  Throws io::BadFile naming the path for a missing, unreadable or bad file.
[[nodiscard]] RunSpec loadRunSpec(const std::filesystem::path& path);

/// A preset: one of the paper's cases (resources/presets/*.json, compiled into core).
struct Preset {
  std::string id;  ///< the file name without its order prefix and suffix, e.g. "k0.1-minute": the CLI's name
  RunSpec spec;    ///< with a name and a description
};

/// Every preset, in file-name order; the first one is the start-up default.
[[nodiscard]] std::span<const Preset> presets();

/// The preset whose id (or name) is `idOrName`, or nullptr.
[[nodiscard]] const Preset* findPreset(std::string_view idOrName);

}  // namespace archipelago
