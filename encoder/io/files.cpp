#include "encoder/io/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "codec/common/error.h"
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

// Creates "<path>.tmp.<random>" exclusively (O_EXCL|O_NOFOLLOW: a planted file or link at
// that name is never opened) and registers it for the signal handler. -1 on failure.
int create_temporary(const std::string& path, std::string* tmp) {
  for (int attempt = 0; attempt < 64; ++attempt) {
    *tmp = path + ".tmp." + random_suffix();
    SignalBlock block;
    if (!set_temporary_file(*tmp)) {
      errno = ENAMETOOLONG;
      return -1;
    }
    const int fd = open(tmp->c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    clear_temporary_file();
    if (errno != EEXIST) return -1;
  }
  return -1;
}

bool write_all(int fd, const void* data, size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= size_t(n);
  }
  return true;
}

void discard_temporary(const std::string& tmp) {
  SignalBlock block;
  unlink(tmp.c_str());
  clear_temporary_file();
}

}  // namespace

std::string lowercase_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

const char* file_type_name(unsigned st_mode) {
  return S_ISREG(st_mode)                        ? "a regular file"
         : S_ISLNK(st_mode)                      ? "a symbolic link"
         : S_ISDIR(st_mode)                      ? "a folder"
         : S_ISFIFO(st_mode)                     ? "a FIFO"
         : S_ISCHR(st_mode) || S_ISBLK(st_mode) ? "a device"
         : S_ISSOCK(st_mode)                     ? "a socket"
                                                 : "not a regular file";
}

bool check_input_file(const std::string& path, std::string* error) {
  struct stat st;
  if (stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return fail(error, path + ": no such file");
    return fail(error, path + ": cannot open: " + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) return true;
  return fail(error, path + ": is " + file_type_name(st.st_mode) + ", not a regular file");
}

namespace {

bool read_exactly(int fd, uint8_t* data, size_t size) {
  while (size > 0) {
    const ssize_t n = read(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= size_t(n);
  }
  return true;
}

// Reads the regular file open as `fd` once its type and size are known to be acceptable.
bool read_open_file(const std::string& path, int fd, std::vector<uint8_t>* bytes, uint64_t max_bytes,
                    std::string* error) {
  struct stat st;
  if (fstat(fd, &st) != 0) return fail(error, path + ": cannot read: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) return fail(error, path + ": is " + std::string(file_type_name(st.st_mode)) + ", not a regular file");
  if (uint64_t(st.st_size) > max_bytes)
    return fail(error, path + ": " + std::to_string(st.st_size) + " bytes, more than the limit of " +
                           std::to_string(max_bytes) + " (--max-memory)");
  const int flags = fcntl(fd, F_GETFL);
  if (flags >= 0) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  bytes->resize(size_t(st.st_size));
  if (!read_exactly(fd, bytes->data(), bytes->size()))
    return fail(error, path + ": cannot read (" + std::strerror(errno) + ", or the file shrank)");
  return true;
}

}  // namespace

bool read_file(const std::string& path, std::vector<uint8_t>* bytes, std::string* error, uint64_t max_bytes) {
  // Non-blocking, so opening a FIFO with no writer returns at once and fstat refuses it.
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return fail(error, path + ": no such file");
    return fail(error, path + ": cannot open: " + std::strerror(errno));
  }
  const bool ok = read_open_file(path, fd, bytes, max_bytes, error);
  close(fd);
  return ok;
}

bool check_output_path(const std::string& path, std::string* error) {
  struct stat st;
  if (lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return true;
    return fail(error, path + ": cannot check the output: " + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) return true;
  return fail(error, path + ": the output exists and is " + std::string(file_type_name(st.st_mode)) +
                         "; refusing to replace it");
}

bool is_one_of(const std::string& path, const std::vector<std::string>& inputs) {
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (std::filesystem::equivalent(path, in, ec) && !ec) return true;
  }
  return false;
}

bool write_file_atomic(const std::string& path, const void* data, size_t size, std::string* error) {
  if (!check_output_path(path, error)) return false;
  std::string tmp;
  const int fd = create_temporary(path, &tmp);
  if (fd < 0) return fail(error, path + ": cannot create a temporary file beside it: " + std::strerror(errno));
  bool ok = write_all(fd, data, size);
  int saved = errno;
  if (close(fd) != 0 && ok) ok = false, saved = errno;
  if (ok && rename(tmp.c_str(), path.c_str()) == 0) {
    clear_temporary_file();
    return true;
  }
  if (ok) saved = errno;
  discard_temporary(tmp);
  return fail(error, path + ": write failed: " + std::strerror(saved));
}

}  // namespace dcurve
