#include "bench/draco_frame.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <cmath>
#include <memory>

#include "codec/common/error.h"

namespace dcurve::bench {
namespace {

// Calibration positions spell each vertex's index as (v mod 1024, v div 1024, 0); 20 bits
// put both on a grid fine enough to round back exactly for up to 2^20 vertices.
constexpr int kCalibrationBits = 20;
constexpr uint32_t kIndexRadix = 1024;
constexpr uint32_t kMaxVertices = kIndexRadix * kIndexRadix;

// A Draco mesh with one point per input vertex (identity mapping, no deduplication, so the
// encoder sees exactly our vertices).
std::unique_ptr<draco::Mesh> make_mesh(uint32_t V, const std::vector<uint32_t>& faces, const float* xyz) {
  auto mesh = std::make_unique<draco::Mesh>();
  mesh->set_num_points(V);
  draco::GeometryAttribute pos;
  pos.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  const int pos_id = mesh->AddAttribute(pos, true, V);
  for (uint32_t v = 0; v < V; ++v)
    mesh->attribute(pos_id)->SetAttributeValue(draco::AttributeValueIndex(v), xyz + 3 * size_t(v));
  mesh->SetNumFaces(faces.size() / 3);
  for (size_t f = 0; f < faces.size() / 3; ++f) {
    draco::Mesh::Face face;
    for (int c = 0; c < 3; ++c) face[c] = draco::PointIndex(faces[3 * f + c]);
    mesh->SetFace(draco::FaceIndex(uint32_t(f)), face);
  }
  return mesh;
}

bool encode_mesh(const draco::Mesh& mesh, int bits, std::vector<char>* file, std::string* error) {
  draco::Encoder enc;
  enc.SetSpeedOptions(0, 0);  // compression level 10
  enc.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
  enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
  draco::EncoderBuffer buf;
  const draco::Status st = enc.EncodeMeshToBuffer(mesh, &buf);
  if (!st.ok()) return fail(error, std::string("Draco encode failed: ") + st.error_msg());
  file->assign(buf.data(), buf.data() + buf.size());
  return true;
}

std::unique_ptr<draco::Mesh> decode_mesh(const std::vector<char>& file, std::string* error) {
  draco::DecoderBuffer buf;
  buf.Init(file.data(), file.size());
  draco::Decoder dec;
  auto so = dec.DecodeMeshFromBuffer(&buf);
  if (!so.ok()) {
    fail(error, std::string("Draco decode failed: ") + so.status().error_msg());
    return nullptr;
  }
  return std::move(so).value();
}

std::vector<uint32_t> face_points(const draco::Mesh& mesh) {
  std::vector<uint32_t> out;
  out.reserve(size_t(mesh.num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) out.push_back(mesh.face(f)[c].value());
  return out;
}

}  // namespace

bool DracoFrameCodec::init(uint32_t V, const std::vector<uint32_t>& faces, std::string* error) {
  if (V > kMaxVertices) return fail(error, "Draco baselines support at most 2^20 vertices");
  vertex_count_ = V;
  faces_ = faces;
  std::vector<float> index_xyz(size_t(V) * 3, 0.f);
  for (uint32_t v = 0; v < V; ++v) {
    index_xyz[3 * size_t(v)] = float(v % kIndexRadix);
    index_xyz[3 * size_t(v) + 1] = float(v / kIndexRadix);
  }
  std::vector<char> file;
  if (!encode_mesh(*make_mesh(V, faces, index_xyz.data()), kCalibrationBits, &file, error)) return false;
  auto mesh = decode_mesh(file, error);
  if (!mesh) return false;
  const draco::PointAttribute* pos = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (!pos) return fail(error, "Draco calibration file has no positions");
  point_to_vertex_.resize(mesh->num_points());
  std::vector<char> seen(V, 0);
  for (draco::PointIndex p(0); p < mesh->num_points(); ++p) {
    float xyz[3];
    pos->GetMappedValue(p, xyz);
    const double v = std::nearbyint(xyz[0]) + double(kIndexRadix) * std::nearbyint(xyz[1]);
    if (!(v >= 0 && v < V) || std::fabs(xyz[0] - std::nearbyint(xyz[0])) > 0.25f)
      return fail(error, "Draco calibration decoded an unreadable vertex index");
    point_to_vertex_[p.value()] = uint32_t(v);
    seen[uint32_t(v)] = 1;
  }
  for (uint32_t v = 0; v < V; ++v)
    if (!seen[v])
      return fail(error, "Draco dropped vertex " + std::to_string(v) + " (used by no triangle?)");
  decoded_faces_ = face_points(*mesh);

  const std::vector<float> flat(size_t(V) * 3, 0.f);
  if (!encode_mesh(*make_mesh(V, faces, flat.data()), kCalibrationBits, &file, error)) return false;
  connectivity_bytes_ = file.size();
  return true;
}

bool DracoFrameCodec::encode(const float* xyz, int bits, std::vector<char>* file, std::string* error) const {
  return encode_mesh(*make_mesh(vertex_count_, faces_, xyz), bits, file, error);
}

bool DracoFrameCodec::decode(const std::vector<char>& file, std::vector<float>* xyz, std::string* error,
                             bool verify) const {
  auto mesh = decode_mesh(file, error);
  if (!mesh) return false;
  if (mesh->num_points() != point_to_vertex_.size() || (verify && face_points(*mesh) != decoded_faces_))
    return fail(error, "Draco decoded a vertex order other than the calibration's; cannot match vertices");
  const draco::PointAttribute* pos = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (!pos) return fail(error, "Draco file has no positions");
  xyz->resize(size_t(vertex_count_) * 3);
  for (draco::PointIndex p(0); p < mesh->num_points(); ++p)
    pos->GetMappedValue(p, xyz->data() + 3 * size_t(point_to_vertex_[p.value()]));
  return true;
}

}  // namespace dcurve::bench
