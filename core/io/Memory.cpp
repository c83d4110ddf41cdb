#include "core/io/Memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <limits>
#include <stdexcept>

namespace archipelago::io {

std::uintmax_t availableMemoryBytes() {
  std::uintmax_t available = std::numeric_limits<std::uintmax_t>::max();
  if (std::ifstream meminfo("/proc/meminfo"); meminfo) {
    std::string key;
    std::uintmax_t kib = 0;
    std::string unit;
    while (meminfo >> key >> kib >> unit) {
      if (key == "MemAvailable:") {
        available = kib * 1024;
        break;
      }
    }
  }
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    std::uintmax_t used = 0;
    if (std::ifstream status("/proc/self/statm"); status) {
      std::uintmax_t pages = 0;
      status >> pages;
      used = pages * static_cast<std::uintmax_t>(::sysconf(_SC_PAGESIZE));
    }
    const std::uintmax_t left = limit.rlim_cur > used ? limit.rlim_cur - used : 0;
    if (left < available) available = left;
  }
  return available;
}

void checkMemory(std::uintmax_t bytes, const std::string& what) {
  const std::uintmax_t available = availableMemoryBytes();
  if (bytes > available) {
    constexpr std::uintmax_t MiB = 1 << 20;
    throw NotEnoughMemory(what + " needs about " + std::to_string((bytes + MiB - 1) / MiB) + " MiB of memory but only " +
                             std::to_string(available / MiB) + " MiB are available");
  }
}

}  // namespace archipelago::io
