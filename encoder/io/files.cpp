#include "encoder/io/files.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "codec/common/error.h"

namespace dcurve {

std::string lowercase_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

std::string containing_folder(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
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

bool is_one_of(const std::string& path, const std::vector<std::string>& inputs) {
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (std::filesystem::equivalent(path, in, ec) && !ec) return true;
  }
  return false;
}

}  // namespace dcurve
