#include "cli/staging_dir.h"

#include <stdlib.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/signal_cleanup.h"

namespace dcurve::cli {
namespace fs = std::filesystem;

StagingDir::~StagingDir() {
  if (path_.empty()) return;
  std::error_code ec;
  fs::remove_all(path_, ec);
  set_temporary_folder("");
}

bool StagingDir::create(const std::string& parent, std::string* error) {
  std::string pattern = (fs::path(parent.empty() ? "." : parent) / ".dcurve-partial-XXXXXX").string();
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  SignalBlock block;  // created and registered together, so a signal never leaves it behind
  if (!mkdtemp(buf.data())) return fail(error, parent + ": cannot create a temporary folder: " + std::strerror(errno));
  path_ = buf.data();
  if (!set_temporary_folder(path_)) return fail(error, path_ + ": name too long to register for cleanup");
  return true;
}

bool StagingDir::move_to(const std::string& target, std::string* error) {
  // mkdtemp made it private (0700); the output folder gets the usual permissions.
  const mode_t mask = umask(0);
  umask(mask);
  chmod(path_.c_str(), 0777 & ~mask);
  std::error_code ec;
  SignalBlock block;  // moved and unregistered together
  fs::rename(path_, target, ec);
  if (ec) return fail(error, target + ": cannot move the output into place: " + ec.message());
  path_.clear();
  set_temporary_folder("");
  return true;
}

}  // namespace dcurve::cli
