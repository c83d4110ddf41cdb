// libFuzzer target: tail_state (see FuzzTargets.hpp).  Built by `cmake --preset fuzz`; run by scripts/fuzz.sh.
#include "FuzzTargets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  archipelago::fuzz::tailState(data, size);
  return 0;
}
