#include "chunk_source.h"

#include <mutex>

namespace dcurve {
namespace {

class MemoryChunks : public ChunkSource {
 public:
  MemoryChunks(const uint8_t* data, size_t size) : data_(data, data + size) {}
  const uint8_t* fetch(uint64_t offset, uint64_t size, std::vector<uint8_t>*, Error* error) const override {
    if (offset > data_.size() || size > data_.size() - offset) {
      if (error) *error = {Status::CorruptChunk, "chunk lies outside the chunk data"};
      return nullptr;
    }
    return data_.data() + offset;
  }
  size_t memory_bytes() const override { return data_.capacity(); }

 private:
  std::vector<uint8_t> data_;
};

class FileChunks : public ChunkSource {
 public:
  FileChunks(std::FILE* file, uint64_t data_offset, uint64_t data_size, std::string path)
      : file_(file), data_offset_(data_offset), data_size_(data_size), path_(std::move(path)) {}
  ~FileChunks() override { std::fclose(file_); }

  const uint8_t* fetch(uint64_t offset, uint64_t size, std::vector<uint8_t>* buffer, Error* error) const override {
    if (offset > data_size_ || size > data_size_ - offset) return failed(error, "chunk lies outside the chunk data");
    buffer->resize(size_t(size));
    std::lock_guard<std::mutex> lock(mutex_);
    // The file may have changed since it was opened: a short read means it was truncated
    // (and a rewrite shows in the chunk's checksum, which the caller verifies).
    if (std::fseek(file_, long(data_offset_ + offset), SEEK_SET) != 0 ||
        std::fread(buffer->data(), 1, buffer->size(), file_) != buffer->size()) {
      std::clearerr(file_);
      return failed(error, "cannot read a chunk: the file was truncated or changed after it was opened");
    }
    return buffer->data();
  }
  size_t memory_bytes() const override { return sizeof(*this) + path_.capacity(); }

 private:
  const uint8_t* failed(Error* error, const std::string& why) const {
    if (error) *error = {Status::Io, path_ + ": " + why};
    return nullptr;
  }
  std::FILE* file_;
  uint64_t data_offset_, data_size_;
  std::string path_;
  mutable std::mutex mutex_;
};

}  // namespace

std::unique_ptr<ChunkSource> memory_chunks(const uint8_t* data, size_t size) {
  return std::make_unique<MemoryChunks>(data, size);
}

std::unique_ptr<ChunkSource> file_chunks(std::FILE* file, uint64_t data_offset, uint64_t data_size,
                                         const std::string& path) {
  return std::make_unique<FileChunks>(file, data_offset, data_size, path);
}

}  // namespace dcurve
