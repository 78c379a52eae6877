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
#include <fstream>
#include <iterator>
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

bool read_file(const std::string& path, std::vector<uint8_t>* bytes, std::string* error) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    if (error) *error = path + ": is a folder, not a file";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (error) *error = path + ": cannot open: " + std::strerror(errno);
    return false;
  }
  bytes->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

bool check_output_path(const std::string& path, std::string* error) {
  struct stat st;
  if (lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return true;
    return fail(error, path + ": cannot check the output: " + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) return true;
  const char* what = S_ISLNK(st.st_mode)   ? "a symbolic link"
                     : S_ISDIR(st.st_mode) ? "a folder"
                     : S_ISFIFO(st.st_mode) ? "a FIFO"
                     : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                                  : "not a regular file";
  return fail(error, path + ": the output exists and is " + what + "; refusing to replace it");
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
