#include "encoder/io/output_folder.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <vector>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/output_file.h"
#include "encoder/io/rename.h"
#include "encoder/io/signal_cleanup.h"

namespace dcurve {
namespace fs = std::filesystem;
namespace {

std::string without_trailing_slashes(std::string dir) {
  while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
  return dir;
}

// Opens a folder (never through a link) and takes its lock without waiting; -1 if either fails.
int open_locked(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return -1;
  if (flock(fd, LOCK_EX | LOCK_NB) == 0) return fd;
  const int saved = errno;
  ::close(fd);
  errno = saved;
  return -1;
}

// The staged frames reach the disk before they replace anything: one syncfs for the lot.
bool sync_file_system(int fd) {
#if defined(__linux__)
  return syncfs(fd) == 0;
#else
  (void)fd;
  sync();
  return true;
#endif
}

// A renamed folder entry survives a crash once its folder is synced.
void sync_folder(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  fsync(fd);
  ::close(fd);
}

}  // namespace

bool is_mesh_file_name(const std::string& name) {
  const std::string ext = lowercase_extension(name);
  return ext == ".obj" || ext == ".ply" || ext == ".off";
}

OutputFolder::~OutputFolder() {
  if (!staging_.empty()) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
    set_temporary_folder("");
  }
  for (int fd : {dir_fd_, staging_fd_})
    if (fd >= 0) ::close(fd);
}

bool OutputFolder::check(const std::string& dir, bool replace, std::string* error) {
  OutputFolder folder;
  return folder.inspect(dir, replace, error);
}

bool OutputFolder::open(const std::string& dir, bool replace, std::string* error) {
  return inspect(dir, replace, error) && create_staging(containing_folder(dir_), error);
}

bool OutputFolder::inspect(const std::string& dir, bool replace, std::string* error) {
  dir_ = without_trailing_slashes(dir);
  if (dir_.empty()) return fail(error, "the output folder has no name");
  struct stat st;
  exists_ = lstat(dir_.c_str(), &st) == 0;
  if (!exists_ && errno != ENOENT) return fail(error, dir_ + ": cannot check the output: " + std::strerror(errno));
  if (exists_ && !S_ISDIR(st.st_mode))
    return fail(error, dir_ + (S_ISLNK(st.st_mode) ? ": the output folder is a symbolic link; give the folder itself"
                                                   : ": exists and is not a folder"));
  const std::string parent = containing_folder(dir_);
  std::error_code ec;
  if (!fs::is_directory(parent, ec)) return fail(error, dir_ + ": folder " + parent + " does not exist");
  return !exists_ || check_existing(replace, error);
}

bool OutputFolder::check_existing(bool replace, std::string* error) {
  dir_fd_ = open_locked(dir_);
  if (dir_fd_ < 0)
    return fail(error, dir_ + (errno == EWOULDBLOCK ? ": another process is writing frames into this folder"
                                                    : ": cannot open the output folder: " + std::string(std::strerror(errno))));
  std::vector<std::string> frames;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir_, ec)) {
    const std::string name = e.path().filename().string();
    if (!is_mesh_file_name(name)) continue;
    if (e.is_directory(ec) && !e.is_symlink(ec))
      return fail(error, e.path().string() + ": a folder named like a frame; refusing to replace it");
    frames.push_back(name);
  }
  if (ec) return fail(error, dir_ + ": cannot list the output folder: " + ec.message());
  if (frames.empty() || replace) return true;
  std::sort(frames.begin(), frames.end());  // the message names the first
  return fail(error, dir_ + ": already holds frames (" + frames.front() +
                         ", ...): choose another folder, or --force to replace its frames");
}

bool OutputFolder::create_staging(const std::string& parent, std::string* error) {
  std::string pattern = (fs::path(parent) / ".dcurve-partial-XXXXXX").string();
  SignalBlock block;  // created and registered together, so a signal never leaves it behind
  if (!mkdtemp(pattern.data())) return fail(error, parent + ": cannot create a temporary folder: " + std::strerror(errno));
  staging_ = pattern;
  if (!set_temporary_folder(staging_)) return fail(error, staging_ + ": name too long to register for cleanup");
  staging_fd_ = open_locked(staging_);  // a second writer that finds the swapped-in folder waits for nothing
  return true;
}

std::string OutputFolder::staged(const std::string& name) const { return (fs::path(staging_) / name).string(); }

bool OutputFolder::write_file(const std::string& name, const void* data, size_t size, std::string* error) {
  OutputFile file;
  return file.open(staged(name), false, error, false) && file.write(data, size, error) && file.commit(error);
}

bool OutputFolder::commit(std::string* error) {
  // mkdtemp made the staging folder private (0700): the output gets the old folder's mode, or
  // the usual one.
  struct stat st;
  mode_t mode = 0;
  if (exists_ && fstat(dir_fd_, &st) == 0) {
    mode = st.st_mode & 07777;
  } else {
    mode = umask(0);
    umask(mode);
    mode = 0777 & ~mode;
  }
  chmod(staging_.c_str(), mode);
  if (!sync_file_system(staging_fd_)) return fail(error, dir_ + ": cannot sync the new frames: " + std::strerror(errno));
  if (exists_) return swap_in(error);
  SignalBlock block;  // moved and unregistered together
  if (rename_no_replace(staging_.c_str(), dir_.c_str()) != 0)
    return fail(error, dir_ + (errno == EEXIST || errno == ENOTEMPTY
                                   ? ": appeared while the frames were written (another process?); not replaced"
                                   : ": cannot move the frames into place: " + std::string(std::strerror(errno))));
  staging_.clear();
  set_temporary_folder("");
  sync_folder(containing_folder(dir_));
  return true;
}

// Swaps the folders, then moves what the old one held besides frames into the new one and
// removes the old frames.
bool OutputFolder::swap_in(std::string* error) {
  {
    SignalBlock block;  // after the swap the staging name holds the old folder: never the handler's
    if (rename_exchange(staging_.c_str(), dir_.c_str()) != 0)
      return fail(error, dir_ + ": cannot swap the new frames in: " + std::strerror(errno));
    set_temporary_folder("");
  }
  const std::string old = staging_;
  staging_.clear();
  sync_folder(containing_folder(dir_));
  std::error_code ec;
  std::vector<fs::path> entries;  // listed first: the loop below changes the folder
  for (const auto& e : fs::directory_iterator(old, ec)) entries.push_back(e.path());
  for (const fs::path& entry : entries) {
    const fs::path target = fs::path(dir_) / entry.filename();
    if (is_mesh_file_name(entry.filename().string())) {
      fs::remove(entry, ec);
    } else if (rename_no_replace(entry.c_str(), target.c_str()) != 0) {
      return fail(error, target.string() + ": cannot move it back from " + old + ": " + std::strerror(errno));
    }
  }
  fs::remove(old, ec);
  return !ec || fail(error, old + ": the old frames' folder cannot be removed: " + ec.message());
}

}  // namespace dcurve
