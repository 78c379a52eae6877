#include "encoder/io/gltf_accessor.h"

#include <tiny_gltf.h>

#include <cstring>

#include "codec/common/error.h"
#include "encoder/io/read_limits.h"

namespace dcurve {
namespace {

// An accessor without a bufferView is all zeros plus its sparse values; this bounds what a
// file of a few bytes can make the reader allocate.
constexpr size_t kMaxViewlessElements = size_t(1) << 26;

// Where `count` elements of `element_bytes` each, `stride` apart, lie in a buffer view.
struct Span {
  const uint8_t* data = nullptr;
  size_t stride = 0;
};

bool locate(const tinygltf::Model& model, int view_index, size_t offset, size_t count, size_t element_bytes,
            size_t stride, const std::string& what, Span* span, std::string* error) {
  if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
    return fail(error, what + ": bufferView " + std::to_string(view_index) + " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[view_index];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
    return fail(error, what + ": buffer " + std::to_string(view.buffer) + " does not exist");
  const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
  // glTF 2.0 section 3.6.2.4: a stride holds at least one element and is 4-byte aligned.
  if (stride != 0 && (stride < element_bytes || stride % 4 != 0))
    return fail(error, what + ": byteStride " + std::to_string(stride) + " is " +
                           (stride < element_bytes ? "smaller than its element (" + std::to_string(element_bytes) + " bytes)"
                                                   : std::string("not a multiple of 4")));
  if (stride == 0) stride = element_bytes;
  // Bounded before multiplying, so a hostile count cannot wrap around.
  const bool fits = view.byteOffset <= data.size() && view.byteLength <= data.size() - view.byteOffset &&
                    count <= view.byteLength && offset <= view.byteLength;
  const size_t need = count == 0 ? 0 : offset + (count - 1) * stride + element_bytes;
  if (!fits || need > view.byteLength)
    return fail(error, what + ": its data runs past the end of its buffer (truncated or compressed buffer?)");
  span->data = data.data() + view.byteOffset + offset;
  span->stride = stride;
  return true;
}

// The bufferView's byteStride, 0 (packed) for a view that does not exist (locate refuses it).
size_t view_stride(const tinygltf::Model& model, int view) {
  return view >= 0 && size_t(view) < model.bufferViews.size() ? model.bufferViews[view].byteStride : 0;
}

uint32_t load_index(const uint8_t* p, int component_type) {
  if (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return *p;
  if (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
    uint16_t v;
    std::memcpy(&v, p, 2);
    return v;
  }
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

size_t index_bytes(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return 4;
    default: return 0;
  }
}

// Bytes of one component of an attribute: FLOAT, or the normalized unsigned integers glTF
// allows for texture coordinates and colours; 0 for other types.
size_t attribute_component_bytes(const tinygltf::Accessor& a, bool allow_normalized = true) {
  if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return 4;
  if (!a.normalized || !allow_normalized) return 0;
  if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return 1;
  if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) return 2;
  return 0;
}

// `components` values of one element at p, as floats (normalized integers scaled to [0, 1]).
void load_element(const uint8_t* p, int component_type, int components, float* out) {
  for (int c = 0; c < components; ++c) {
    if (component_type == TINYGLTF_COMPONENT_TYPE_FLOAT) std::memcpy(out + c, p + 4 * c, 4);
    else if (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) out[c] = float(p[c]) / 255.0f;
    else out[c] = float(load_index(p + 2 * c, component_type)) / 65535.0f;
  }
}

// Replaces the elements the sparse part lists (glTF 2.0 section 3.6.2.3).
bool apply_sparse(const tinygltf::Model& model, const tinygltf::Accessor& a, int components, const std::string& what,
                  std::vector<float>* out, std::string* error) {
  const auto& s = a.sparse;
  const size_t ib = index_bytes(s.indices.componentType), element = attribute_component_bytes(a) * components;
  if (s.count <= 0 || size_t(s.count) > a.count || ib == 0)
    return fail(error, what + ": sparse accessor with a count or index type dcurve cannot read");
  Span idx, val;
  if (!locate(model, s.indices.bufferView, size_t(s.indices.byteOffset), size_t(s.count), ib, 0, what + " (sparse indices)", &idx, error) ||
      !locate(model, s.values.bufferView, size_t(s.values.byteOffset), size_t(s.count), element, 0,
              what + " (sparse values)", &val, error))
    return false;
  int64_t previous = -1;
  for (int i = 0; i < s.count; ++i) {
    const uint32_t at = load_index(idx.data + i * ib, s.indices.componentType);
    if (at >= a.count || int64_t(at) <= previous)
      return fail(error, what + ": sparse index " + std::to_string(at) + " is out of range or not increasing");
    previous = at;
    load_element(val.data + size_t(i) * element, a.componentType, components, out->data() + size_t(at) * components);
  }
  return true;
}

const tinygltf::Accessor* find_accessor(const tinygltf::Model& model, int index, const std::string& what,
                                        std::string* error) {
  if (index < 0 || size_t(index) >= model.accessors.size()) {
    fail(error, what + ": accessor " + std::to_string(index) + " does not exist");
    return nullptr;
  }
  return &model.accessors[index];
}

}  // namespace

bool read_float_accessor(const tinygltf::Model& model, int index, int components, const std::string& what,
                         MemoryBudget* budget, std::vector<float>* out, std::string* error, bool allow_normalized) {
  static const char* const kTypeNames[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
  static const int kTypes[] = {0, TINYGLTF_TYPE_SCALAR, TINYGLTF_TYPE_VEC2, TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4};
  const tinygltf::Accessor* a = find_accessor(model, index, what, error);
  if (!a) return false;
  if (components < 1 || components > 4) return fail(error, what + ": unsupported element size");
  const size_t component_bytes = attribute_component_bytes(*a, allow_normalized);
  if (a->type != kTypes[components] || component_bytes == 0)
    return fail(error, what + ": accessor " + std::to_string(index) + " is not " + kTypeNames[components] +
                           (allow_normalized ? " FLOAT or normalized unsigned" : " FLOAT") + " (quantized data, e.g. KHR_mesh_quantization, is not read)");
  if (a->bufferView < 0 && a->count > kMaxViewlessElements)
    return fail(error, what + ": accessor " + std::to_string(index) + " has no data and " + std::to_string(a->count) + " elements");
  if (a->bufferView >= 0 && size_t(a->bufferView) < model.bufferViews.size() &&
      a->count > model.bufferViews[a->bufferView].byteLength)
    return fail(error, what + ": accessor " + std::to_string(index) + " counts more elements than its bufferView holds");
  if (!budget->take(a->count, 4 * uint64_t(components), what, error)) return false;
  out->assign(a->count * components, 0.0f);
  if (a->bufferView >= 0) {  // without a view, the values are zeros (then sparse)
    Span span;
    if (!locate(model, a->bufferView, a->byteOffset, a->count, component_bytes * size_t(components),
                view_stride(model, a->bufferView), what, &span, error))
      return false;
    for (size_t i = 0; i < a->count; ++i)
      load_element(span.data + i * span.stride, a->componentType, components, out->data() + i * components);
  }
  return !a->sparse.isSparse || apply_sparse(model, *a, components, what, out, error);
}

bool read_index_accessor(const tinygltf::Model& model, int index, MemoryBudget* budget, std::vector<uint32_t>* out,
                         std::string* error) {
  const tinygltf::Accessor* a = find_accessor(model, index, "indices", error);
  if (!a) return false;
  const size_t bytes = index_bytes(a->componentType);
  if (a->type != TINYGLTF_TYPE_SCALAR || bytes == 0 || a->sparse.isSparse || a->bufferView < 0)
    return fail(error, "indices: accessor " + std::to_string(index) +
                           " is not a plain SCALAR of unsigned byte, short or int (sparse indices are not read)");
  Span span;
  if (!locate(model, a->bufferView, a->byteOffset, a->count, bytes, view_stride(model, a->bufferView), "indices", &span,
              error))
    return false;
  if (!budget->take(a->count, 4, "indices", error)) return false;
  out->resize(a->count);
  for (size_t i = 0; i < a->count; ++i) (*out)[i] = load_index(span.data + i * span.stride, a->componentType);
  return true;
}

}  // namespace dcurve
