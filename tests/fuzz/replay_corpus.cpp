// Replays the fuzzers' seed corpus (tests/fuzz/corpus/<target>/*) and any crash reproducers through the same
// entry points, with whatever compiler built the test suite: every input that ever found a bug stays a test.
//   replay_corpus <target> <file-or-folder>…
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "FuzzTargets.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: replay_corpus runfile|runspec|numbers|session|manifest|tail|tail_state PATH…\n");
    return 2;
  }
  const std::string target = argv[1];
  void (*entry)(const std::uint8_t*, std::size_t) = target == "runfile"   ? archipelago::fuzz::runFile
                                                    : target == "runspec" ? archipelago::fuzz::runSpec
                                                    : target == "numbers" ? archipelago::fuzz::numbers
                                                    : target == "session" ? archipelago::fuzz::session
                                                    : target == "manifest" ? archipelago::fuzz::manifest
                                                    : target == "tail"    ? archipelago::fuzz::tailFile
                                                    : target == "tail_state" ? archipelago::fuzz::tailState
                                                                          : nullptr;
  if (!entry) {
    std::fprintf(stderr, "unknown target %s\n", target.c_str());
    return 2;
  }
  std::vector<std::filesystem::path> files;
  for (int i = 2; i < argc; ++i) {
    if (std::filesystem::is_directory(argv[i])) {
      for (const auto& e : std::filesystem::recursive_directory_iterator(argv[i]))
        if (e.is_regular_file()) files.push_back(e.path());
    } else {
      files.emplace_back(argv[i]);
    }
  }
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("%s: %zu inputs replayed, no failure\n", target.c_str(), files.size());
  return files.empty() ? 1 : 0;
}
