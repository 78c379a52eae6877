// A fresh private folder beside an output (mkdtemp: created, never reused, not a symlink),
// where a multi-file output is written before it is moved into place. Whatever is still in
// it when it goes out of scope is removed, so a failed decode leaves nothing behind; a
// SIGINT, SIGTERM or SIGHUP removes it too (encoder/io/signal_cleanup). One at a time.
#pragma once
#include <string>

namespace dcurve::cli {

class StagingDir {
 public:
  StagingDir() = default;
  StagingDir(const StagingDir&) = delete;
  StagingDir& operator=(const StagingDir&) = delete;
  ~StagingDir();

  // Creates the folder in `parent` (which must exist).
  bool create(const std::string& parent, std::string* error);
  const std::string& path() const { return path_; }
  // Renames the staging folder itself to `target` (which must not exist); it is then kept.
  bool move_to(const std::string& target, std::string* error);

 private:
  std::string path_;
};

}  // namespace dcurve::cli
