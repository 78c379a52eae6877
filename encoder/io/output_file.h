// The one way dcurve writes an output file (.dcrv, meshes, glTF, point caches, the frames of a
// folder): a new temporary file beside the target, created exclusively and never through a
// link (O_CREAT|O_EXCL|O_NOFOLLOW) under a name that fits the file system's name limit, written,
// fsync'd and renamed over the target in one step. Readers never see a partial file, a failed
// or interrupted write leaves nothing (encoder/io/signal_cleanup), a link or special file at
// the target is refused, and without `replace` the rename never replaces a file that appeared
// meanwhile (two writers: the second fails).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace dcurve {

// Whether `path` may become an output: absent, or a regular file when `replace`. A symbolic
// link, FIFO, device, socket or folder there is always refused; a regular file without
// `replace` is refused with a hint at --force. The error names the path.
bool check_output_path(const std::string& path, bool replace, std::string* error);

// The temporary's name for `path`: in the same folder, the file name cut (at a UTF-8
// character) so that name + ".tmp." + `random` fits `name_max` bytes.
std::string temporary_name(const std::string& path, const std::string& random, size_t name_max);

class OutputFile {
 public:
  OutputFile() = default;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();  // an uncommitted temporary is removed

  // Checks `path` (check_output_path) and creates its temporary. One open file at a time per
  // process (the signal handler removes one). `sync`: fsync at the commit (a folder's frames
  // skip it: OutputFolder syncs them all at once).
  bool open(const std::string& path, bool replace, std::string* error, bool sync = true);
  bool write(const void* data, size_t size, std::string* error);
  // Overwrites bytes already written (a header whose sizes are known only at the end).
  bool write_at(uint64_t offset, const void* data, size_t size, std::string* error);
  uint64_t bytes_written() const { return written_; }
  const std::string& path() const { return path_; }
  // fsync, close and rename into place (without `replace`: only while the target is absent).
  bool commit(std::string* error);

 private:
  bool failed(const std::string& what, std::string* error);
  void discard();
  std::string path_, tmp_;
  int fd_ = -1;
  bool replace_ = false, sync_ = true;
  uint64_t written_ = 0;
};

// The whole of `data` through an OutputFile that replaces a regular file at `path`.
bool write_file_atomic(const std::string& path, const void* data, size_t size, std::string* error);

}  // namespace dcurve
