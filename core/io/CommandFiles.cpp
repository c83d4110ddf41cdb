#include "core/io/CommandFiles.hpp"

#include <sys/stat.h>

#include <stdexcept>

#include "core/io/AtomicFile.hpp"

namespace archipelago::io {

namespace {
/// What a path names: a device and inode when it exists, else the path its links lead to, in a resolved folder.
struct Identity {
  bool stream = false;  // a device or FIFO: written through, replaces nothing
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::filesystem::path resolved;

  [[nodiscard]] bool sameFileAs(const Identity& o) const {
    if (stream || o.stream || exists != o.exists) return false;
    return exists ? device == o.device && inode == o.inode : resolved == o.resolved;
  }
};

Identity identityOf(const std::filesystem::path& path) {
  Identity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.stream = S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode);
    id.exists = true;
    id.device = st.st_dev;
    id.inode = st.st_ino;
    return id;
  }
  std::filesystem::path target = path;
  try {
    target = resolveOutputTarget(path).path;  // a dangling link: the file it would create
  } catch (const std::runtime_error&) {
  }
  std::error_code ec;
  const std::filesystem::path folder = std::filesystem::weakly_canonical(
      target.has_parent_path() ? target.parent_path() : std::filesystem::path("."), ec);
  id.resolved = ec ? target.lexically_normal() : folder / target.filename();
  return id;
}

bool written(FileUse use) { return use == FileUse::Output || use == FileUse::SavedState; }
bool state(FileUse use) { return use == FileUse::ResumedState || use == FileUse::SavedState; }
std::string named(const CommandFile& f) { return f.option + " " + f.path.string(); }
}  // namespace

std::optional<std::string> commandFilesError(const std::vector<CommandFile>& files) {
  std::vector<const CommandFile*> given;
  for (const CommandFile& f : files)
    if (!f.path.empty()) given.push_back(&f);
  for (const CommandFile* f : given) {
    if (!written(f->use)) continue;
    try {
      checkWritableTarget(f->path);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
  }
  std::vector<Identity> ids;
  for (const CommandFile* f : given) ids.push_back(identityOf(f->path));
  for (std::size_t i = 0; i < given.size(); ++i)
    for (std::size_t j = i + 1; j < given.size(); ++j) {
      const CommandFile& a = *given[i];
      const CommandFile& b = *given[j];
      if (!ids[i].sameFileAs(ids[j]) || (state(a.use) && state(b.use))) continue;
      if (written(a.use) && written(b.use))
        return named(a) + " and " + named(b) + " are one file: give each output its own file";
      if (written(a.use) || written(b.use)) {
        const CommandFile& out = written(a.use) ? a : b;
        const CommandFile& in = written(a.use) ? b : a;
        return named(out) + " is also an input (" + named(in) +
               "): write to another file (a command never writes over what it reads)";
      }
      return named(a) + " and " + named(b) + " are one file: give each input once (it would be counted twice)";
    }
  return std::nullopt;
}

void checkCommandFiles(const std::vector<CommandFile>& files) {
  if (auto e = commandFilesError(files)) throw std::invalid_argument(*e);
}

}  // namespace archipelago::io
