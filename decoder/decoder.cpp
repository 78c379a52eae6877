#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>
#include <vector>

#include "codec/common/container_format.h"
#include "codec/common/error.h"
#include "codec/common/residual.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/model_prediction.h"
#include "codec/decompress/residual_decoder.h"
#include "decoder_state.h"
#include "normals.h"
#include "dcurve.hpp"

namespace dcurve {

struct Cursor::State {
  explicit State(const SharedState& shared) : window(shared) {}
  ChunkWindow window;
};

namespace {

bool open_failed(std::string* error, Status* status, Status code, const std::string& message) {
  if (error) *error = message;
  if (status) *status = code;
  return false;
}

// Builds what every cursor shares once the file's head is parsed into shared->model
// (residual.payload holding the chunk index): the index, the traversal and the model tables.
bool prepare(SharedState* shared, uint64_t file_bytes, std::string* error) {
  const Model& m = shared->model;
  const uint64_t budget = decoder_value_budget(size_t(std::min<uint64_t>(file_bytes, SIZE_MAX)));
  if (m.residual.step > 0) {
    const std::vector<uint8_t>& p = m.residual.payload;
    if (!read_residual_index(p.data(), p.size(), m.meta.frame_count, !m.faces.empty(), m.residual.external_bytes,
                             &shared->index, error))
      return false;
    // A cursor holds a decoded chunk: bounded like every other table by the file size.
    if (uint64_t(shared->index.chunk_frames) * m.meta.vertex_count * 3 * 2 > budget)
      return fail(error, "chunks are implausibly large for the file size");
    // A fast payload (format 4) reads no neighbours; the low-rank basis builds its own.
    if (shared->fast()) shared->fast_traversal = fast_traversal(m.faces, m.meta.vertex_count);
    else shared->traversal = build_traversal(m);
  }
  build_render_state(&shared->model, &shared->render);
  const bool has_traversal = m.residual.step > 0 && !shared->fast();
  if (!shared->predictor.build(m, budget, error, has_traversal ? &shared->traversal : nullptr,
                               shared->fast() ? &shared->fast_traversal : nullptr))
    return false;
  // The predictor holds the decoded basis: its coded form is read no more.
  std::vector<uint8_t>().swap(shared->model.low_rank.basis_payload);
  // The traversals are built, so only a motion model reads the curves again (a file
  // without CURV has one-point curves: three arrays of V values).
  if (!has_motion_model(m)) shared->model.curves = Curves();
  return true;
}

}  // namespace

Decoder::Decoder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Decoder::~Decoder() = default;

std::unique_ptr<Decoder> Decoder::open_memory(const void* data, size_t size, std::string* error, Status* status) {
  if (status) *status = Status::Ok;
  if (!data && size) {
    open_failed(error, status, Status::InvalidArgument, "null data");
    return nullptr;
  }
  try {
    auto impl = std::make_unique<Impl>();
    const uint8_t* bytes = static_cast<const uint8_t*>(data);
    std::string why;
    if (!read_container_head(bytes, size, size, &impl->shared.model, &why) ||
        !prepare(&impl->shared, size, &why)) {
      open_failed(error, status, Status::Malformed, why);
      return nullptr;
    }
    const uint64_t chunk_bytes = impl->shared.model.residual.external_bytes;
    impl->shared.chunks = memory_chunks(bytes + (size - chunk_bytes), size_t(chunk_bytes));
    return std::unique_ptr<Decoder>(new Decoder(std::move(impl)));
  } catch (const std::bad_alloc&) {
    open_failed(error, status, Status::OutOfMemory, "out of memory");
    return nullptr;
  }
}

namespace {
struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

bool read_at(std::FILE* f, uint64_t offset, size_t size, std::vector<uint8_t>* out) {
  out->resize(size);
  return std::fseek(f, long(offset), SEEK_SET) == 0 && std::fread(out->data(), 1, size, f) == size;
}
}  // namespace

std::unique_ptr<Decoder> Decoder::open_file(const std::string& path, std::string* error, Status* status) {
  if (status) *status = Status::Ok;
  try {
    FilePtr file(std::fopen(path.c_str(), "rb"));
    // Unbuffered: every chunk read goes to the file, so a change after opening is seen (a
    // stdio buffer could still hold a small file's old bytes).
    if (file) std::setvbuf(file.get(), nullptr, _IONBF, 0);
    if (!file || std::fseek(file.get(), 0, SEEK_END) != 0) {
      open_failed(error, status, Status::Io, path + ": cannot open file");
      return nullptr;
    }
    const long end = std::ftell(file.get());
    if (end < 0) {
      open_failed(error, status, Status::Io, path + ": cannot read file");
      return nullptr;
    }
    const uint64_t file_bytes = uint64_t(end);
    // The header says how much precedes the chunks: read that, leave the chunks in the file.
    std::vector<uint8_t> head;
    ContainerHeader header;
    std::string why;
    if (!read_at(file.get(), 0, size_t(std::min<uint64_t>(file_bytes, kContainerHeaderBytes)), &head) ||
        !read_container_header(head.data(), head.size(), file_bytes, &header, &why) ||
        !read_at(file.get(), 0, size_t(header.head_bytes), &head)) {
      open_failed(error, status, why.empty() ? Status::Io : Status::Malformed,
                  path + ": " + (why.empty() ? "cannot read file" : why));
      return nullptr;
    }
    auto impl = std::make_unique<Impl>();
    if (!read_container_head(head.data(), head.size(), file_bytes, &impl->shared.model, &why) ||
        !prepare(&impl->shared, file_bytes, &why)) {
      open_failed(error, status, Status::Malformed, path + ": " + why);
      return nullptr;
    }
    impl->shared.chunks = file_chunks(file.release(), header.head_bytes, file_bytes - header.head_bytes, path);
    return std::unique_ptr<Decoder>(new Decoder(std::move(impl)));
  } catch (const std::bad_alloc&) {
    open_failed(error, status, Status::OutOfMemory, path + ": out of memory");
    return nullptr;
  }
}

uint32_t Decoder::vertex_count() const { return impl_->shared.model.meta.vertex_count; }
uint32_t Decoder::frame_count() const { return impl_->shared.model.meta.frame_count; }
uint32_t Decoder::face_count() const { return uint32_t(impl_->shared.model.faces.size() / 3); }
const uint32_t* Decoder::faces() const {
  const auto& faces = impl_->shared.model.faces;
  return faces.empty() ? nullptr : faces.data();
}
double Decoder::frame_rate() const { return impl_->shared.model.meta.frame_rate; }
double Decoder::tolerance() const { return impl_->shared.model.meta.tolerance; }
double Decoder::rest_diagonal() const { return impl_->shared.model.meta.diag; }
uint32_t Decoder::chunk_frames() const { return impl_->shared.index.chunk_frames; }
uint32_t Decoder::chunk_count() const { return uint32_t(impl_->shared.index.chunks.size()); }
Interpolation Decoder::interpolation() const { return Interpolation(int(impl_->shared.model.meta.inbetween)); }

void Decoder::set_interpolation(Interpolation rule) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->rule = Inbetween(uint8_t(rule));
  impl_->rule_set = true;
  if (impl_->window) impl_->window->set_inbetween(impl_->rule);
}

namespace {
ChunkWindow& internal_window(Decoder::Impl& impl) {
  if (!impl.window) {
    impl.window = std::make_unique<ChunkWindow>(impl.shared);
    if (impl.rule_set) impl.window->set_inbetween(impl.rule);
  }
  return *impl.window;
}

// Frame coordinate of time t; clamping happens in frame coordinates (NaN maps to frame 0).
double frame_coordinate(double t, uint32_t frame_count) { return t * double(frame_count - 1); }

bool evaluate_guarded(ChunkWindow& window, double x, float* out, Error* error) {
  try {
    return window.evaluate(x, out, error);
  } catch (const std::bad_alloc&) {
    if (error) *error = {Status::OutOfMemory, "out of memory"};
    return false;
  }
}
}  // namespace

bool Decoder::evaluate(double t, float* xyz, Error* error) const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return evaluate_guarded(internal_window(*impl_), frame_coordinate(t, frame_count()), xyz, error);
}

bool Decoder::evaluate_frame(uint32_t f, float* xyz, Error* error) const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return evaluate_guarded(internal_window(*impl_), double(std::min(f, frame_count() - 1)), xyz, error);
}

std::unique_ptr<Cursor> Decoder::make_cursor() const {
  return std::unique_ptr<Cursor>(new Cursor(std::make_unique<Cursor::State>(impl_->shared)));
}

size_t Decoder::memory_bytes() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return sizeof(*this) + sizeof(Impl) + impl_->shared.memory_bytes() +
         (impl_->window ? impl_->window->memory_bytes() : 0);
}

bool Decoder::compute_normals(const float* xyz, float* normals) const {
  const auto& faces = impl_->shared.model.faces;
  if (faces.empty()) return false;
  area_normals(xyz, faces.data(), faces.size(), faces.data(), vertex_count(), normals);
  return true;
}

Cursor::Cursor(std::unique_ptr<State> state) : state_(std::move(state)) {}
Cursor::~Cursor() = default;

bool Cursor::evaluate(double t, float* xyz, Error* error) {
  const uint32_t F = state_->window.frame_count();
  return evaluate_guarded(state_->window, frame_coordinate(t, F), xyz, error);
}

bool Cursor::evaluate_frame(uint32_t f, float* xyz, Error* error) {
  const uint32_t F = state_->window.frame_count();
  return evaluate_guarded(state_->window, double(std::min(f, F - 1)), xyz, error);
}

void Cursor::set_interpolation(Interpolation rule) { state_->window.set_inbetween(Inbetween(uint8_t(rule))); }

size_t Cursor::memory_bytes() const { return sizeof(*this) + sizeof(State) + state_->window.memory_bytes(); }

uint32_t version() { return DCURVE_VERSION; }

}  // namespace dcurve
