#include "encoder/io/output_file.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <random>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/rename.h"
#include "encoder/io/signal_cleanup.h"

namespace dcurve {
namespace {

std::string random_suffix() {
  static std::mt19937_64 rng{std::random_device{}() ^ (uint64_t(getpid()) << 32)};
  static const char kDigits[] = "0123456789abcdefghijklmnopqrstuvwxyz";
  std::string s(10, '0');
  for (char& c : s) c = kDigits[rng() % 36];
  return s;
}

// The longest file name the output's folder takes (255 on the usual file systems).
size_t name_max_of(const std::string& path) {
  const long n = pathconf(containing_folder(path).c_str(), _PC_NAME_MAX);
  return n > 16 ? size_t(n) : 255;
}

// Creates a fresh temporary for `path` and registers it for the signal handler; -1 on failure.
int create_temporary(const std::string& path, std::string* tmp) {
  const size_t name_max = name_max_of(path);
  for (int attempt = 0; attempt < 64; ++attempt) {
    *tmp = temporary_name(path, random_suffix(), name_max);
    SignalBlock block;  // created and registered together, so a signal never leaves it behind
    if (!set_temporary_file(*tmp)) {
      errno = ENAMETOOLONG;
      return -1;
    }
    const int fd = ::open(tmp->c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    const int saved = errno;
    clear_temporary_file();
    errno = saved;
    if (errno != EEXIST) return -1;
  }
  return -1;
}

}  // namespace

bool check_output_path(const std::string& path, bool replace, std::string* error) {
  struct stat st;
  if (lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return true;
    return fail(error, path + ": cannot check the output: " + std::strerror(errno));
  }
  if (!S_ISREG(st.st_mode))
    return fail(error, path + ": the output exists and is " + file_type_name(st.st_mode) + "; refusing to replace it");
  if (!replace) return fail(error, path + ": the output exists; --force replaces it");
  return true;
}

std::string temporary_name(const std::string& path, const std::string& random, size_t name_max) {
  const std::filesystem::path p(path);
  std::string name = p.filename().string();
  const std::string suffix = ".tmp." + random;
  size_t keep = name_max > suffix.size() ? name_max - suffix.size() : 0;
  if (name.size() > keep) {
    while (keep > 0 && (static_cast<unsigned char>(name[keep]) & 0xC0) == 0x80) --keep;  // not inside a character
    name.resize(keep);
  }
  return (p.parent_path() / (name + suffix)).string();
}

OutputFile::~OutputFile() { discard(); }

void OutputFile::discard() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (tmp_.empty()) return;
  SignalBlock block;
  unlink(tmp_.c_str());
  clear_temporary_file();
  tmp_.clear();
}

bool OutputFile::failed(const std::string& what, std::string* error) {
  const int saved = errno;
  discard();
  return fail(error, path_ + ": " + what + ": " + std::strerror(saved));
}

bool OutputFile::open(const std::string& path, bool replace, std::string* error, bool sync) {
  discard();
  path_ = path;
  replace_ = replace;
  sync_ = sync;
  written_ = 0;
  if (!check_output_path(path, replace, error)) return false;
  fd_ = create_temporary(path, &tmp_);
  if (fd_ < 0) {
    tmp_.clear();
    return failed("cannot create a temporary file beside it", error);
  }
  return true;
}

bool OutputFile::write(const void* data, size_t size, std::string* error) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd_, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return failed("write failed", error);
    p += n;
    size -= size_t(n);
    written_ += uint64_t(n);
  }
  return true;
}

bool OutputFile::write_at(uint64_t offset, const void* data, size_t size, std::string* error) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::pwrite(fd_, p, size, off_t(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return failed("write failed", error);
    p += n;
    size -= size_t(n);
    offset += uint64_t(n);
  }
  return true;
}

bool OutputFile::commit(std::string* error) {
  if (sync_ && fsync(fd_) != 0) return failed("write failed", error);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) return failed("write failed", error);
  SignalBlock block;  // renamed and unregistered together
  const int moved = replace_ ? std::rename(tmp_.c_str(), path_.c_str()) : rename_no_replace(tmp_.c_str(), path_.c_str());
  if (moved != 0)
    return failed(errno == EEXIST ? "appeared while it was written (another process?); not replaced"
                                  : "cannot move into place",
                  error);
  clear_temporary_file();
  tmp_.clear();
  return true;
}

bool write_file_atomic(const std::string& path, const void* data, size_t size, std::string* error) {
  OutputFile out;
  return out.open(path, true, error) && out.write(data, size, error) && out.commit(error);
}

}  // namespace dcurve
