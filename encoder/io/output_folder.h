// A folder of frames written as a whole. The frames go into a fresh private staging folder
// beside the target (mkdtemp: `.dcurve-partial-XXXXXX`), each through an OutputFile; at the
// end the staging folder becomes the target (a new folder: renamed, never over one that
// appeared meanwhile) or is swapped with it in one step (an existing folder: its frames, the
// mesh files, go; whatever else it holds moves over). So readers see the old frames or the
// new ones, never a mix, and a failure at any point before the swap leaves the old folder as
// it was. An existing target is locked (flock) from open to the end: a second writer fails
// at once. A SIGINT, SIGTERM or SIGHUP removes the staging folder (encoder/io/signal_cleanup).
#pragma once
#include <cstddef>
#include <string>

namespace dcurve {

// Whether a folder entry is a frame: a file (not a folder) named .obj, .ply or .off.
bool is_mesh_file_name(const std::string& name);

class OutputFolder {
 public:
  OutputFolder() = default;
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  ~OutputFolder();  // the staging folder, unless committed, goes with what it holds

  // Checks `dir` (absent, or a folder that holds no frames unless `replace`; a link or a
  // special file is refused), locks it and creates the staging folder beside it.
  bool open(const std::string& dir, bool replace, std::string* error);
  // What open checks, without locking or staging (before long work; open checks again).
  static bool check(const std::string& dir, bool replace, std::string* error);
  // Where the frame `name` is written before the commit.
  std::string staged(const std::string& name) const;
  // Writes the frame `name` (an OutputFile in the staging folder, synced with the others at
  // the commit: one syncfs rather than an fsync per frame).
  bool write_file(const std::string& name, const void* data, size_t size, std::string* error);
  // Puts the staged frames in place of the folder's old ones.
  bool commit(std::string* error);

 private:
  bool inspect(const std::string& dir, bool replace, std::string* error);
  bool check_existing(bool replace, std::string* error);
  bool create_staging(const std::string& parent, std::string* error);
  bool swap_in(std::string* error);
  std::string dir_, staging_;
  bool exists_ = false;
  int dir_fd_ = -1, staging_fd_ = -1;  // held open for their locks
};

}  // namespace dcurve
