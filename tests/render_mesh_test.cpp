// Render vertices (REND) and placement (PLAC): seam copies welded and decoded at one
// position, attributes within their precision, normals shared across UV seams but not hard
// edges, the face coder's reordering followed, face groups and materials, every rejection of
// dcrv.md sections 19-21.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "codec/common/bytes.h"
#include "codec/common/render_format.h"
#include "codec/common/render_mesh.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/render_reader.h"
#include "container_bytes.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/io/weld.h"
#include "test_util.h"

namespace dcurve {
namespace {

// An open tube of `around` x `rows` quads whose UV seam repeats the first column as a last
// one (u = 1): render vertex (i, j) is i + j * (around + 1). Frames breathe in radius.
struct Tube {
  Animation anim;
  std::vector<AnimationRender::Attribute> attributes;
  uint32_t around, rows;
};

Tube make_tube(uint32_t around, uint32_t rows, uint32_t frames, bool hard_seam = false) {
  Tube t{{}, {}, around, rows};
  const uint32_t columns = around + 1, R = columns * (rows + 1);
  Animation& a = t.anim;
  a.vertex_count = R;
  a.frame_rate = 24;
  AnimationRender::Attribute uv{AttributeSemantic::TexCoord0, 2, {}}, normal{AttributeSemantic::Normal, 3, {}};
  for (uint32_t j = 0; j <= rows; ++j)
    for (uint32_t i = 0; i < columns; ++i) {
      const double angle = 2 * M_PI * (i % around) / around;
      uv.values.insert(uv.values.end(), {float(i) / around, float(j) / rows});
      // A hard seam: the copy at u = 1 has a normal of its own, as an exporter writes a crease.
      const bool crease = hard_seam && i == around;
      normal.values.insert(normal.values.end(), {crease ? 0.f : float(std::cos(angle)), crease ? 1.f : 0.f,
                                                 crease ? 0.f : float(std::sin(angle))});
    }
  for (uint32_t f = 0; f < frames; ++f) {
    std::vector<float> xyz;
    for (uint32_t j = 0; j <= rows; ++j)
      for (uint32_t i = 0; i < columns; ++i) {
        const double angle = 2 * M_PI * (i % around) / around, r = 0.5 + 0.05 * std::sin(0.7 * f + j);
        xyz.insert(xyz.end(), {float(r * std::cos(angle)), float(j) / rows, float(r * std::sin(angle))});
      }
    a.frames.push_back(xyz);
  }
  for (uint32_t j = 0; j < rows; ++j)
    for (uint32_t i = 0; i < around; ++i) {
      const uint32_t v = j * columns + i;
      a.faces.insert(a.faces.end(), {v, v + columns, v + 1, v + 1, v + columns, v + columns + 1});
    }
  t.attributes = {uv, normal};
  return t;
}

// Refused at open, or the same positions and render data whose ids stay in bounds.
bool testing_refused_or_same(const std::vector<uint8_t>& file, const Decoder& original, size_t* refused) {
  std::string err;
  auto dec = Decoder::open_memory(file.data(), file.size(), &err);
  if (!dec) return ++*refused, true;
  if (!test::refused_or_decodes_as(file, original)) return false;
  std::vector<float> xyz(3 * size_t(dec->vertex_count())), r(3 * size_t(dec->render_vertex_count())), n(r.size());
  if (!dec->evaluate_frame(0, xyz.data())) return true;
  dec->render_positions(xyz.data(), r.data());
  dec->compute_render_normals(xyz.data(), n.data());
  for (size_t k = 0; dec->render_faces() && k < 3 * size_t(dec->face_count()); ++k)
    if (dec->render_faces()[k] >= dec->render_vertex_count()) return false;
  uint32_t grouped = 0;
  for (uint32_t g = 0; g < dec->group_count(); ++g) grouped += dec->group(g).face_count;
  return dec->group_count() == 0 || grouped == dec->face_count();
}

std::vector<uint8_t> encode(const Animation& anim) {
  EncodeOptions o;
  o.grid_refinement = 2;
  o.low_rank = 0;
  o.threads = 1;
  std::vector<uint8_t> bytes;
  EncodeReport rep;
  std::string err;
  EXPECT_TRUE(encode_animation(anim, o, &bytes, &rep, &err)) << err;
  return bytes;
}

TEST(RenderMesh, SeamCopiesWeldIntoOneVertexAndKeepTheirOrder) {
  Tube t = make_tube(8, 3, 4);
  const Animation before = t.anim;
  weld_copies(&t.anim, t.attributes);
  EXPECT_EQ(t.anim.vertex_count, 8u * 4);  // 9 x 4 render vertices, one column twice
  ASSERT_EQ(t.anim.render.source.size(), size_t(before.vertex_count));
  for (size_t f = 0; f < t.anim.frames.size(); ++f)
    for (uint32_t r = 0; r < before.vertex_count; ++r)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(t.anim.frames[f][3 * t.anim.render.source[r] + k], before.frames[f][3 * r + k]);
  EXPECT_TRUE(render_source_in_first_use_order(t.anim.render.source, t.anim.vertex_count));
  EXPECT_EQ(t.anim.render.source[8], t.anim.render.source[0]);  // (8, 0) is the copy of (0, 0)
  EXPECT_EQ(t.anim.render.corners, before.faces);              // corners are the input's index buffer
}

TEST(RenderMesh, ACopyThatMovesApartInOneFrameIsNotWelded) {
  Tube t = make_tube(6, 2, 3);
  t.anim.frames[2][3 * 6] += 1e-6f;  // render vertex (6, 0), the copy of (0, 0), in frame 2 only
  weld_copies(&t.anim, t.attributes);
  EXPECT_EQ(t.anim.vertex_count, 6u * 3 + 1);
}

TEST(RenderMesh, TrianglesWeldedToZeroAreaAreDroppedWithANote) {
  Tube t = make_tube(4, 1, 2);
  const uint32_t columns = 5;
  // A sliver between the seam copies: its corners 0 and 4 sit at one point in every frame.
  t.anim.faces.insert(t.anim.faces.end(), {0, 4, columns});
  const size_t triangles = t.anim.faces.size() / 3;
  weld_copies(&t.anim, t.attributes);
  EXPECT_EQ(t.anim.faces.size() / 3, triangles - 1);
  EXPECT_EQ(t.anim.render.corners.size(), t.anim.faces.size());
  ASSERT_EQ(t.anim.notes.size(), 1u);
}

TEST(RenderMesh, DecodedCopiesShareTheirPositionUvsWithinPrecisionPlacementBack) {
  Tube t = make_tube(12, 4, 6);
  const Animation render_input = t.anim;
  weld_copies(&t.anim, t.attributes);
  t.anim.placement.start_time = 1.0 / 24;
  t.anim.placement.has_matrix = true;
  t.anim.placement.matrix[13] = 1.2;
  t.anim.placement.node_name = "cloth";
  t.anim.placement.mesh_name = "tube";
  const std::vector<uint8_t> bytes = encode(t.anim);
  std::string err;
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(dec) << err;
  const uint32_t R = render_input.vertex_count;
  ASSERT_EQ(dec->render_vertex_count(), R);
  ASSERT_EQ(dec->attribute_components(Attribute::TexCoord0), 2u);
  const float* uv = dec->uvs();
  const double uv_limit = 1.0 / (2 * 16383) + 1e-6;  // 14 bits over the range [0, 1]
  for (size_t i = 0; i < 2 * size_t(R); ++i) EXPECT_NEAR(uv[i], t.attributes[0].values[i], uv_limit) << i;
  EXPECT_EQ(dec->colors(), nullptr);
  // The render triangles are the input's, as the face coder ordered them.
  std::vector<std::array<uint32_t, 3>> in, out;
  for (size_t k = 0; k < render_input.faces.size(); k += 3)
    in.push_back({render_input.faces[k], render_input.faces[k + 1], render_input.faces[k + 2]});
  for (size_t k = 0; k < 3 * size_t(dec->face_count()); k += 3) {
    std::array<uint32_t, 3> tri = {dec->render_faces()[k], dec->render_faces()[k + 1], dec->render_faces()[k + 2]};
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    out.push_back(tri);
  }
  for (auto& tri : in) std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
  std::sort(in.begin(), in.end());
  std::sort(out.begin(), out.end());
  EXPECT_EQ(in, out);
  std::vector<float> xyz(3 * size_t(dec->vertex_count())), rxyz(3 * size_t(R)), normals(3 * size_t(R));
  const double limit = 1e-3 * dec->rest_diagonal() * 1.0001;
  for (uint32_t f = 0; f < dec->frame_count(); ++f) {
    ASSERT_TRUE(dec->evaluate_frame(f, xyz.data()));
    dec->render_positions(xyz.data(), rxyz.data());
    ASSERT_TRUE(dec->compute_render_normals(xyz.data(), normals.data()));
    for (uint32_t j = 0; j <= t.rows; ++j) {
      const size_t first = j * (t.around + 1), copy = first + t.around;
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(rxyz[3 * first + k], rxyz[3 * copy + k]);        // seam copies: distance 0
        EXPECT_EQ(normals[3 * first + k], normals[3 * copy + k]);  // and one smooth normal
      }
    }
    for (size_t i = 0; i < rxyz.size(); i += 3) {
      const double dx = rxyz[i] - render_input.frames[f][i], dy = rxyz[i + 1] - render_input.frames[f][i + 1],
                   dz = rxyz[i + 2] - render_input.frames[f][i + 2];
      EXPECT_LE(std::sqrt(dx * dx + dy * dy + dz * dz), limit);
    }
  }
  double matrix[16];
  EXPECT_TRUE(dec->world_matrix(matrix));
  EXPECT_EQ(matrix[13], 1.2);
  EXPECT_EQ(matrix[0], 1.0);
  EXPECT_EQ(dec->start_time(), 1.0 / 24);
  EXPECT_EQ(dec->node_name(), "cloth");
  EXPECT_EQ(dec->mesh_name(), "tube");
}

TEST(RenderMesh, AHardEdgeInTheInputNormalsKeepsTwoNormals) {
  Tube t = make_tube(8, 2, 3, true);
  weld_copies(&t.anim, t.attributes);
  const std::vector<uint8_t> bytes = encode(t.anim);
  std::string err;
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(dec) << err;
  std::vector<float> xyz(3 * size_t(dec->vertex_count())), normals(3 * size_t(dec->render_vertex_count()));
  ASSERT_TRUE(dec->evaluate_frame(1, xyz.data()));
  ASSERT_TRUE(dec->compute_render_normals(xyz.data(), normals.data()));
  // Each copy's normal comes from its own side's triangles alone: they differ.
  const size_t first = 9, copy = 9 + 8;  // row 1
  const double dot = normals[3 * first] * normals[3 * copy] + normals[3 * first + 1] * normals[3 * copy + 1] +
                     normals[3 * first + 2] * normals[3 * copy + 2];
  EXPECT_LT(dot, 0.99);
}

TEST(RenderMesh, AFileWithoutRenderDataHasRenderVerticesThatAreItsVertices) {
  Tube t = make_tube(6, 2, 3);
  for (uint32_t j = 0; j <= t.rows; ++j) t.anim.frames[1][3 * (j * 7 + 6)] += 0.01f;  // every seam copy moves apart
  weld_copies(&t.anim, {});
  ASSERT_TRUE(t.anim.render.empty());
  const std::vector<uint8_t> bytes = encode(t.anim);
  EXPECT_EQ(testing::split_file(bytes).minor, kFormatVersionMinor);  // no REND, no PLAC: still 3.2
  std::string err;
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(dec) << err;
  EXPECT_EQ(dec->render_vertex_count(), dec->vertex_count());
  EXPECT_EQ(dec->render_source(), nullptr);
  EXPECT_EQ(dec->render_faces(), nullptr);
  EXPECT_EQ(dec->uvs(), nullptr);
  double matrix[16];
  EXPECT_FALSE(dec->world_matrix(matrix));
  EXPECT_EQ(matrix[5], 1.0);
}

// REND payloads for a model of 3 vertices and one triangle, written field by field.
struct RendBytes {
  std::vector<uint64_t> source = {0, 0, 0, 3};  // render 3 copies vertex 0
  std::vector<uint64_t> ordinals = {1, 0, 0};   // the triangle's first corner takes the copy
  uint8_t version = render_format::kVersion;
  int64_t render_count = -1;                    // -1: source.size()
  std::vector<uint8_t> attribute;               // one attribute record, or none
  std::vector<std::pair<uint64_t, std::string>> groups;  // material code, name
  std::vector<uint64_t> face_groups;            // per triangle, with groups

  std::vector<uint8_t> bytes() const {
    ByteWriter w;
    w.u8(version);
    w.varint(render_count < 0 ? source.size() : uint64_t(render_count));
    for (uint64_t v : source) w.varint(v);
    for (uint64_t j : ordinals) w.varint(j);
    w.u8(attribute.empty() ? 0 : 1);
    w.bytes(attribute.data(), attribute.size());
    w.varint(groups.size());
    for (const auto& [material, name] : groups) {
      w.varint(material);
      w.str(name);
    }
    for (uint64_t g : face_groups) w.varint(g);
    return std::move(w.data());
  }
};

std::vector<uint8_t> uv_record(uint8_t semantic, uint8_t components, uint8_t bits, float lo, float hi,
                               std::vector<int64_t> deltas) {
  ByteWriter w;
  w.u8(semantic);
  w.u8(components);
  w.u8(bits);
  for (uint8_t c = 0; c < components; ++c) {
    w.f32(lo);
    w.f32(hi);
  }
  for (int64_t d : deltas) w.varint(zigzag_encode(d));
  return std::move(w.data());
}

bool parses(const std::vector<uint8_t>& payload, Model* m = nullptr) {
  Model local;
  Model& model = m ? *m : local;
  model.meta.vertex_count = 3;
  model.faces = {0, 1, 2};
  ByteReader r(payload.data(), payload.size());
  return parse_render(r, &model) && r.remaining() == 0;
}

TEST(RenderMesh, ParsesAWellFormedPayload) {
  RendBytes b;
  b.attribute = uv_record(0, 2, 4, 0.f, 1.f, {1, 2, 3, 4, 15, -15, 0, 5});
  Model m;
  ASSERT_TRUE(parses(b.bytes(), &m));
  EXPECT_EQ(m.render.source, (std::vector<uint32_t>{0, 1, 2, 0}));
  EXPECT_EQ(m.render.corners, (std::vector<uint32_t>{3, 1, 2}));
  // Stored component by component, held vertex by vertex.
  EXPECT_EQ(m.render.attributes[0].q, (std::vector<uint16_t>{1, 15, 3, 0, 6, 0, 10, 5}));
}

TEST(RenderMesh, RejectsEveryMalformedPayload) {
  auto with = [](auto edit) {
    RendBytes b;
    b.attribute = uv_record(0, 2, 4, 0.f, 1.f, std::vector<int64_t>(8, 1));
    edit(b);
    return b.bytes();
  };
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.version = 2; })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.render_count = 2; })));                // R < V
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.render_count = 1000; })));             // more than the bytes
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.source = {0, 2, 0, 0}; })));           // d beyond next
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.source = {0, 0, 0, 0}; })));           // a fourth new vertex
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.source = {0, 0, 1, 1}; })));           // vertex 2 never shown
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.ordinals = {2, 0, 0}; })));            // vertex 0 has 2 copies
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.ordinals = {0, 1, 0}; })));            // vertex 1 has 1
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.attribute = uv_record(4, 2, 4, 0, 1, std::vector<int64_t>(8, 1)); })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.attribute = uv_record(0, 3, 4, 0, 1, std::vector<int64_t>(12, 1)); })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.attribute = uv_record(0, 2, 0, 0, 1, std::vector<int64_t>(8, 0)); })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.attribute = uv_record(0, 2, 17, 0, 1, std::vector<int64_t>(8, 1)); })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.attribute = uv_record(0, 2, 4, 1, 0, std::vector<int64_t>(8, 1)); })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.attribute = uv_record(0, 2, 4, 0, NAN, std::vector<int64_t>(8, 1)); })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.attribute = uv_record(0, 2, 4, 0, 1, {16, 0, 0, 0, 0, 0, 0, 0}); })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.attribute = uv_record(0, 2, 4, 0, 1, {-1, 0, 0, 0, 0, 0, 0, 0}); })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.attribute = uv_record(0, 2, 4, 0, 1, {1, 1, 1, 1, 1, 1, 1}); })));
  std::vector<uint8_t> extra = with([](RendBytes&) {});
  extra.push_back(0);
  EXPECT_FALSE(parses(extra));
  Model no_faces;
  no_faces.meta.vertex_count = 3;
  const std::vector<uint8_t> good = with([](RendBytes&) {});
  ByteReader r(good.data(), good.size());
  EXPECT_FALSE(parse_render(r, &no_faces));
}

TEST(RenderMesh, GroupsParseAndEveryMalformedGroupIsRejected) {
  RendBytes b;
  b.groups = {{0, ""}, {3, "cloth"}};
  b.face_groups = {1};
  Model m;
  ASSERT_TRUE(parses(b.bytes(), &m));
  ASSERT_EQ(m.render.groups.size(), 2u);
  EXPECT_EQ(m.render.groups[0].material, -1);
  EXPECT_EQ(m.render.groups[1].material, 2);
  EXPECT_EQ(m.render.groups[1].name, "cloth");
  EXPECT_EQ(m.render.face_group, (std::vector<uint32_t>{1}));
  auto with = [](auto edit) {
    RendBytes b;
    b.groups = {{0, ""}, {1, "a"}};
    b.face_groups = {0};
    edit(b);
    return b.bytes();
  };
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.face_groups = {2}; })));                 // no group 2
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.face_groups = {}; })));                  // missing
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.groups[1].first = uint64_t(1) << 31; })));  // material past int32
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.groups[1].second.assign(render_format::kMaxNameBytes + 1, 'n'); })));
  EXPECT_FALSE(parses(with([](RendBytes& b) { b.groups.resize(40); b.face_groups = {}; })));  // more than the bytes
}

TEST(RenderMesh, MaterialsParseAndEveryMalformedSectionIsRejected) {
  auto payload = [](uint8_t version, const std::string& json, uint64_t count, const std::string& mime, uint64_t size,
                    size_t bytes) {
    ByteWriter w;
    w.u8(version);
    w.str(json);
    w.varint(count);
    if (count > 0) {
      w.str(mime);
      w.varint(size);
      w.bytes(std::string(bytes, 'x').data(), bytes);
    }
    return std::move(w.data());
  };
  auto parses_materials = [](const std::vector<uint8_t>& p, Model* m) {
    ByteReader r(p.data(), p.size());
    return parse_materials(r, m) && r.remaining() == 0;
  };
  Model m;
  ASSERT_TRUE(parses_materials(payload(1, "{}", 1, "image/png", 5, 5), &m));
  EXPECT_EQ(m.materials.json, "{}");
  ASSERT_EQ(m.materials.images.size(), 1u);
  EXPECT_EQ(m.materials.images[0].bytes.size(), 5u);
  EXPECT_FALSE(parses_materials(payload(2, "{}", 1, "image/png", 5, 5), &m));
  EXPECT_FALSE(parses_materials(payload(1, "{}", 1, "image/png", 6, 5), &m));   // past the end
  EXPECT_FALSE(parses_materials(payload(1, "{}", 1, "image/png", 4, 5), &m));   // a byte left over
  EXPECT_FALSE(parses_materials(payload(1, "{}", 1, std::string(render_format::kMaxMimeBytes + 1, 'm'), 5, 5), &m));
  EXPECT_FALSE(parses_materials(payload(1, "{}", 100, "image/png", 5, 5), &m));  // more images than bytes
  std::vector<uint8_t> long_json = payload(1, "{}", 0, "", 0, 0);
  long_json[1] = 100;  // the JSON's length past the end
  EXPECT_FALSE(parses_materials(long_json, &m));
}

TEST(RenderMesh, MaterialsWithoutRenderVerticesAreRejected) {
  Tube t = make_tube(6, 2, 3);
  weld_copies(&t.anim, t.attributes);
  t.anim.render.groups = {{0, "cloth"}};
  t.anim.render.face_group.assign(t.anim.faces.size() / 3, 0);
  t.anim.materials.json = R"({"materials":[{"name":"cloth"}]})";
  const std::vector<uint8_t> bytes = encode(t.anim);
  testing::RawFile file = testing::split_file(bytes);
  bool had_materials = false;
  for (size_t s = 0; s < file.sections.size(); ++s)
    if (file.sections[s].tag == "REND") file.sections.erase(file.sections.begin() + std::ptrdiff_t(s--));
    else had_materials |= file.sections[s].tag == "MATL";
  ASSERT_TRUE(had_materials);
  const std::vector<uint8_t> out = testing::assemble(file);
  Model m;
  std::string err;
  EXPECT_FALSE(read_container(out.data(), out.size(), &m, &err));
  EXPECT_NE(err.find("materials without render vertices"), std::string::npos) << err;
}

TEST(RenderMesh, PlacementRejectsWhatItsSectionForbids) {
  auto payload = [](uint8_t version, double start, uint8_t has_matrix, double entry, size_t name_bytes) {
    ByteWriter w;
    w.u8(version);
    w.f64(start);
    w.u8(has_matrix);
    if (has_matrix == 1)
      for (int i = 0; i < 16; ++i) w.f64(i == 5 ? entry : 1.0);
    w.str(std::string(name_bytes, 'a'));
    w.str("node");
    return std::move(w.data());
  };
  auto parses_placement = [](const std::vector<uint8_t>& p, Model* m) {
    ByteReader r(p.data(), p.size());
    return parse_placement(r, m) && r.remaining() == 0;
  };
  Model m;
  ASSERT_TRUE(parses_placement(payload(1, 0.5, 1, 2.0, 4), &m));
  EXPECT_EQ(m.placement.start_time, 0.5);
  EXPECT_EQ(m.placement.matrix[5], 2.0);
  EXPECT_EQ(m.placement.node_name, "node");
  EXPECT_FALSE(parses_placement(payload(2, 0.5, 1, 2.0, 4), &m));
  EXPECT_FALSE(parses_placement(payload(1, INFINITY, 1, 2.0, 4), &m));
  EXPECT_FALSE(parses_placement(payload(1, 0.5, 2, 2.0, 4), &m));
  EXPECT_FALSE(parses_placement(payload(1, 0.5, 1, NAN, 4), &m));
  EXPECT_FALSE(parses_placement(payload(1, 0.5, 1, 2.0, render_format::kMaxNameBytes + 1), &m));
}

// A damaged REND or PLAC (with a fresh CRC, so the parser itself must judge) is refused, or
// opens to the same positions with render data that stays in bounds (checked under ASan).
TEST(RenderMesh, ByteFlipsInRenderSectionsAreRefusedOrDecodeTheSame) {
  Tube t = make_tube(6, 2, 3);
  t.anim.render.groups = {{-1, ""}, {0, "cloth"}};
  for (size_t f = 0; f < t.anim.faces.size() / 3; ++f) t.anim.render.face_group.push_back(f % 2);
  weld_copies(&t.anim, t.attributes);
  t.anim.materials.json = R"({"materials":[{"name":"cloth"}],"images":[{"mimeType":"image/png"}]})";
  t.anim.materials.images = {{"image/png", {1, 2, 3, 4}}};
  t.anim.placement.node_name = "n";
  const std::vector<uint8_t> bytes = encode(t.anim);
  std::string err;
  auto original = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(original) << err;
  testing::RawFile file = testing::split_file(bytes);
  EXPECT_EQ(file.minor, kRenderFormatVersionMinor);
  size_t refused = 0, flips = 0;
  for (size_t s = 0; s < file.sections.size(); ++s) {
    if (file.sections[s].tag != "REND" && file.sections[s].tag != "PLAC" && file.sections[s].tag != "MATL") continue;
    EXPECT_EQ(file.sections[s].flags & 1, 0) << "optional";
    for (size_t i = 0; i < file.sections[s].stored.size(); ++i, ++flips) {
      testing::RawFile damaged = file;
      damaged.sections[s].stored[i] ^= 0x5a;
      const std::vector<uint8_t> out = testing::assemble(damaged);
      EXPECT_TRUE(testing_refused_or_same(out, *original, &refused)) << file.sections[s].tag << " byte " << i;
    }
  }
  EXPECT_GT(flips, 0u);
  EXPECT_GT(refused, 0u);
}

}  // namespace
}  // namespace dcurve
