// core/io: SHA-256 against the FIPS 180-4 / NIST test vectors; atomic writes; bounded reads that say what a
// path is instead of hanging on it.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <fcntl.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/io/Sha256.hpp"

namespace archipelago::io {
namespace {

TEST(Sha256, MatchesTheNistVectors) {
  EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256Hex(std::string(1'000'000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // 55, 56 and 64 bytes: the padding's edge cases (one or two final blocks).
  EXPECT_EQ(sha256Hex(std::string(55, 'a')), "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
  EXPECT_EQ(sha256Hex(std::string(56, 'a')), "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
  EXPECT_EQ(sha256Hex(std::string(64, 'a')), "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
}

class IoFiles : public ::testing::Test {
 protected:
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("archipelago-io-" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(IoFiles, AtomicWriteReplacesAndLeavesNoTemporaryFile) {
  writeFileAtomically(dir / "a.txt", "first");
  writeFileAtomically(dir / "a.txt", "second");
  EXPECT_EQ(readRegularFile(dir / "a.txt", 100), "second");
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  EXPECT_THROW(writeFileAtomically(dir / "missing" / "a.txt", "x"), std::runtime_error);
}

namespace {
int filesIn(const std::filesystem::path& dir) {
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  return files;
}
}  // namespace

// Issue 12, finding 7: replay's CSV (and PNGs) were streamed straight into the target, which a full disk or a
// kill left truncated.  A streamed file is invisible until commit(); without commit() the old one stays.
TEST_F(IoFiles, StreamedAtomicOutputIsPublishedOnlyByCommit) {
  const auto target = dir / "seg.csv";
  writeFileAtomically(target, "old");
  {
    AtomicOutputFile file(target);
    file.stream() << "step,x\n";
    for (int i = 0; i < 1000; ++i) file.stream() << i << ",0.5\n";
    EXPECT_EQ(readRegularFile(target, 100), "old");  // readers see the old file until commit
    EXPECT_EQ(filesIn(dir), 2);                       // the target and one temporary beside it
    file.commit();
  }
  EXPECT_EQ(filesIn(dir), 1);
  EXPECT_EQ(readRegularFile(target, 1 << 20).substr(0, 9), "step,x\n0,");
  {
    AtomicOutputFile abandoned(target);  // e.g. an exception while replaying
    abandoned.stream() << "half";
  }
  EXPECT_EQ(filesIn(dir), 1);
  EXPECT_EQ(readRegularFile(target, 1 << 20).substr(0, 6), "step,x");
  EXPECT_THROW(AtomicOutputFile(dir / "missing" / "a.csv"), std::runtime_error);
  std::filesystem::permissions(target, std::filesystem::perms::owner_read | std::filesystem::perms::group_read |
                                           std::filesystem::perms::others_read);
  EXPECT_THROW(AtomicOutputFile{target}, std::runtime_error);  // a 0444 target is never replaced
}

// Issue 12, finding 7: a full disk left a truncated or 0-byte output.  RLIMIT_FSIZE makes writes fail as a full
// disk does (EFBIG instead of ENOSPC): commit() throws naming the file, the old file stays, no temporary is left.
TEST_F(IoFiles, StreamedAtomicOutputOnAFullDiskKeepsTheOldFile) {
  const auto target = dir / "full.csv";
  writeFileAtomically(target, "old");
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = saved;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  bool threw = false;
  try {
    AtomicOutputFile file(target);
    for (int i = 0; i < 10000; ++i) file.stream() << "0123456789\n";
    file.commit();
  } catch (const std::runtime_error& e) {
    threw = std::string(e.what()).find(target.string()) != std::string::npos;
  }
  ::setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, previous);
  EXPECT_TRUE(threw);
  EXPECT_EQ(readRegularFile(target, 100), "old");
  EXPECT_EQ(filesIn(dir), 1);
}

TEST_F(IoFiles, BoundedReadNamesWhatThePathIs) {
  const auto expectError = [](const std::filesystem::path& p, std::uintmax_t max, const std::string& mention) {
    try {
      (void)readRegularFile(p, max);
      ADD_FAILURE() << p;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
    }
  };
  expectError(dir, 100, "it is a folder");              // issue 12, finding 8: not "unexpected end of input"
  expectError(dir / "none", 100, "No such file");
  const auto fifo = dir / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expectError(fifo, 100, "it is a FIFO");               // issue 12, finding 6: a FIFO used to hang the reader
  expectError("/dev/zero", 100, "it is a device");      // /dev/zero used to grow until memory ran out
  std::ofstream(dir / "big") << std::string(101, 'x');
  expectError(dir / "big", 100, "101 bytes, more than the 100");
}

// Issue 12, finding 7: output folders were checked only after the whole computation, and a 0444 target was
// silently replaced.
TEST_F(IoFiles, OutputPathsAreCheckedBeforeWork) {
  const auto expectError = [](const std::filesystem::path& p, const std::string& mention) {
    try {
      checkWritableTarget(p);
      ADD_FAILURE() << p;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
    }
  };
  EXPECT_NO_THROW(checkWritableTarget(dir / "new.json"));
  expectError(dir / "typo" / "run.json", "does not exist");
  expectError(dir, "it is a folder");
  std::ofstream(dir / "file") << "x";
  expectError(dir / "file" / "run.json", "is not a folder");
  std::ofstream(dir / "protected.json") << "{}";
  std::filesystem::permissions(dir / "protected.json", std::filesystem::perms::owner_read | std::filesystem::perms::group_read |
                                                          std::filesystem::perms::others_read);
  expectError(dir / "protected.json", "read-only");
}

// Issue 12, finding 7: two runs on the same --out both exited 0, and a killed run resumed from the shared
// checkpoint silently continued the other one.
TEST_F(IoFiles, OneWriterPerFile) {
  const auto target = dir / "run.json";
  {
    FileLock first = FileLock::acquire(target);
    try {
      FileLock second = FileLock::acquire(target);  // another open file description: as another process
      ADD_FAILURE() << "two locks on one file";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("in use by another process"), std::string::npos) << e.what();
    }
    FileLock other = FileLock::acquire(dir / "other.json");  // another file: no conflict
    FileLock moved = std::move(first);                        // still held after a move
    EXPECT_THROW((void)FileLock::acquire(target), std::runtime_error);
  }
  EXPECT_NO_THROW((void)FileLock::acquire(target));  // released with its holder
  EXPECT_FALSE(std::filesystem::exists(dir / ".run.json.lock"));
}

// Issue 12, finding 7: SIGKILL left ".ck.json.XXXXXX" temporaries that were never cleaned.
TEST_F(IoFiles, StaleTemporariesOfTheSameFileAreRemoved) {
  std::ofstream(dir / ".run.json.a1B2c3") << "partial";
  std::ofstream(dir / ".run.json.Zz9Yy8") << "partial";
  std::ofstream(dir / ".run.json.lock") << "";        // not a temporary
  std::ofstream(dir / ".other.json.a1B2c3") << "x";   // another file's
  std::ofstream(dir / "run.json") << "{}";
  EXPECT_EQ(removeStaleTemporaries(dir / "run.json"), 2u);
  EXPECT_TRUE(std::filesystem::exists(dir / ".run.json.lock"));
  EXPECT_TRUE(std::filesystem::exists(dir / ".other.json.a1B2c3"));
  EXPECT_TRUE(std::filesystem::exists(dir / "run.json"));
}


// ---- Issue 36: outputs that fail loudly and never clobber -----------------------------------------------------

bool isCharacterDevice(const std::filesystem::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

// Class 1: an output path that is a link was replaced by a file (the link gone, its target unchanged).  The file it
// leads to is replaced atomically and the link stays; a dangling link creates the file it names.
TEST_F(IoFiles, Issue36Class1ALinkIsFollowedNotReplaced) {
  std::filesystem::create_directories(dir / "real");
  writeFileAtomically(dir / "real" / "a.json", "old");
  std::filesystem::create_symlink("real/a.json", dir / "link.json");
  writeFileAtomically(dir / "link.json", "new");
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.json"));
  EXPECT_EQ(readRegularFile(dir / "real" / "a.json", 100), "new");
  EXPECT_EQ(filesIn(dir / "real"), 1);  // no temporary left beside the target
  std::filesystem::create_symlink("real/b.json", dir / "dangling.json");
  writeFileAtomically(dir / "dangling.json", "created");
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "dangling.json"));
  EXPECT_EQ(readRegularFile(dir / "real" / "b.json", 100), "created");
  std::filesystem::create_symlink("loop2", dir / "loop1");
  std::filesystem::create_symlink("loop1", dir / "loop2");
  EXPECT_THROW(checkWritableTarget(dir / "loop1"), std::runtime_error);
}

// Class 1: as root, `--out /dev/null` and `--out /dev/full` renamed a regular file over the device node.  A device is
// written through: /dev/null takes the bytes, /dev/full reports its error, and both stay devices.  A link to them in
// a private folder is used, so that a regression replaces the link, never the real node.
TEST_F(IoFiles, Issue36Class1ADeviceIsWrittenThroughNeverReplaced) {
  std::filesystem::create_symlink("/dev/null", dir / "null.npy");
  writeFileAtomically(dir / "null.npy", std::string(100000, 'x'));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "null.npy"));
  EXPECT_TRUE(isCharacterDevice("/dev/null"));
  EXPECT_EQ(filesIn(dir), 1);
  {
    FileLock lock = FileLock::acquire(dir / "null.npy");  // no lock file beside a device (none in /dev)
    EXPECT_EQ(removeStaleTemporaries(dir / "null.npy"), 0u);
  }
  EXPECT_NO_THROW(checkWritableTarget(dir / "null.npy"));
  if (std::filesystem::exists("/dev/full")) {
    std::filesystem::create_symlink("/dev/full", dir / "full.json");
    try {
      writeFileAtomically(dir / "full.json", "{}");
      ADD_FAILURE() << "a write to /dev/full succeeded";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("No space left"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(std::filesystem::is_symlink(dir / "full.json"));
    EXPECT_TRUE(isCharacterDevice("/dev/full"));
  }
  // A private device node (root only: mknod), named directly.
  if (::mknod((dir / "private-null").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    writeFileAtomically(dir / "private-null", "x");
    EXPECT_TRUE(isCharacterDevice(dir / "private-null"));
  }
}

// Class 1: a FIFO is written through to its reader, never replaced by a file.
TEST_F(IoFiles, Issue36Class1AFifoIsWrittenThrough) {
  const auto fifo = dir / "fifo.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(fifo, std::ios::binary);  // opening waits for the writer
    received.assign(std::istreambuf_iterator<char>(in), {});
  });
  const std::string content(200000, 'y');  // more than a pipe's buffer
  writeFileAtomically(fifo, content);
  struct stat st {};
  if (::lstat(fifo.c_str(), &st) != 0 || !S_ISFIFO(st.st_mode)) {
    reader.detach();  // blocked for ever on the FIFO that was renamed over: the regression this test guards
    FAIL() << fifo << " was replaced by a file";
  }
  reader.join();
  EXPECT_EQ(received, content);
}

// Class 9: `tail --out` with a 255-byte file name failed on its lock file's name (".NAME.lock" is 261 bytes); the
// temporary ".NAME.XXXXXX" too.  Long names get a short hashed lock and temporary name beside them.
TEST_F(IoFiles, Issue36Class9AFileNameOf255Bytes) {
  const auto target = dir / (std::string(250, 'n') + ".json");
  const auto other = dir / (std::string(250, 'n') + ".jsom");  // the same first 200 bytes: its own names
  ASSERT_EQ(target.filename().string().size(), 255u);
  writeFileAtomically(target, "first");
  EXPECT_EQ(readRegularFile(target, 100), "first");
  {
    FileLock lock = FileLock::acquire(target);
    FileLock otherLock = FileLock::acquire(other);
    EXPECT_THROW((void)FileLock::acquire(target), std::runtime_error);
    AtomicOutputFile abandoned(target);  // a temporary of the long name, as a killed writer leaves it
    abandoned.stream() << "partial";
    abandoned.stream().flush();
    EXPECT_EQ(filesIn(dir), 4);  // the file, two locks, the temporary
    EXPECT_EQ(removeStaleTemporaries(other), 0u);
    EXPECT_EQ(removeStaleTemporaries(target), 1u);  // found by its hashed name
  }
  EXPECT_EQ(filesIn(dir), 1);
}

// Class 5: indicator on a nearly full disk reported an ERROR for the .npy but left the PNG written before it.  In
// a batch, nothing is published until every output is written.
TEST_F(IoFiles, Issue36Class5OutputsOfABatchAreAllOrNothing) {
  writeFileAtomically(dir / "a.png", "old a");
  {
    OutputBatch batch;
    writeFileAtomically(dir / "a.png", "new a");
    EXPECT_EQ(readRegularFile(dir / "a.png", 100), "old a");  // not yet published
    EXPECT_THROW(writeFileAtomically(dir / "missing" / "b.npy", "b"), std::runtime_error);  // the second fails
  }  // the batch is dropped: the first's temporary removed, the old file kept
  EXPECT_EQ(readRegularFile(dir / "a.png", 100), "old a");
  EXPECT_EQ(filesIn(dir), 1);
  {
    OutputBatch batch;
    writeFileAtomically(dir / "a.png", "new a");
    writeFileAtomically(dir / "b.npy", "new b");
    EXPECT_FALSE(std::filesystem::exists(dir / "b.npy"));
    batch.commit();
  }
  EXPECT_EQ(readRegularFile(dir / "a.png", 100), "new a");
  EXPECT_EQ(readRegularFile(dir / "b.npy", 100), "new b");
  EXPECT_EQ(filesIn(dir), 2);
  writeFileAtomically(dir / "c.csv", "c");  // no batch open: published at once
  EXPECT_EQ(readRegularFile(dir / "c.csv", 100), "c");
}

// Class 3: `tail --out o.json --csv o.json` lost the tail file; `tail --compare R --out R` destroyed the run R;
// `tail --compare R R` counted R twice.  One policy for every command: outputs are distinct files, none is an input,
// an input is named once; one run's state files may coincide; devices may be named twice.
TEST_F(IoFiles, Issue36Class3NoOutputOverAnotherOrOverAnInput) {
  writeFileAtomically(dir / "R.json", "{}");
  std::filesystem::create_symlink("R.json", dir / "link.json");
  std::filesystem::create_directories(dir / "sub");
  const auto error = [](const std::vector<CommandFile>& files) { return commandFilesError(files).value_or(""); };
  const auto out = [](std::string option, std::filesystem::path p) { return CommandFile{option, p, FileUse::Output}; };
  const auto in = [](std::string option, std::filesystem::path p) { return CommandFile{option, p, FileUse::Input}; };
  EXPECT_NE(error({out("--out", dir / "o.json"), out("--csv", dir / "o.json")}).find("are one file"), std::string::npos);
  EXPECT_NE(error({out("--out", dir / "o.json"), out("--csv", dir / "sub" / ".." / "o.json")}), "");  // not yet existing
  EXPECT_NE(error({in("--compare", dir / "R.json"), out("--out", dir / "R.json")}).find("is also an input"), std::string::npos);
  EXPECT_NE(error({in("--compare", dir / "R.json"), out("--out", dir / "link.json")}), "");  // through a link
  EXPECT_NE(error({in("--compare", dir / "R.json"), in("--compare", dir / "link.json")}).find("give each input once"),
            std::string::npos);
  EXPECT_EQ(error({in("--compare", dir / "R.json"), out("--out", dir / "T.json"), out("--csv", dir / "T.csv")}), "");
  EXPECT_EQ(error({CommandFile{"--out", dir / "R.json", FileUse::SavedState},
                   CommandFile{"--checkpoint", dir / "link.json", FileUse::SavedState},
                   CommandFile{"--resume", dir / "R.json", FileUse::ResumedState}}), "");  // a run goes on in its file
  EXPECT_NE(error({CommandFile{"--resume", dir / "R.json", FileUse::ResumedState}, out("--csv", dir / "R.json")}), "");
  std::filesystem::create_symlink("/dev/null", dir / "null1");
  EXPECT_EQ(error({out("--out", dir / "null1"), out("--npy", dir / "null1")}), "");  // nothing replaced there
  EXPECT_NE(error({out("--out", dir / "missing" / "o.json")}).find("does not exist"), std::string::npos);
  EXPECT_EQ(error({out("--out", ""), out("--csv", "")}), "");  // options not given
  EXPECT_THROW(checkCommandFiles({out("--out", dir / "x"), out("--csv", dir / "x")}), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago::io
