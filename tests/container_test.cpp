// The .dcrv container: exact round trips, the FACE coder, room to grow, and rejection of
// every malformed file (truncations, byte flips, random bytes, absurd counts).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "codec/common/container_format.h"
#include "codec/common/crc32.h"
#include "codec/common/faces.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/faces_encoder.h"
#include "codec/compress/quantize.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/faces_decoder.h"
#include "container_bytes.h"
#include "encoder/io/frames.h"
#include "test_models.h"
#include "test_util.h"

namespace dcurve {
namespace {

using testing::assemble;
using testing::plain_section;
using testing::RawFile;
using testing::small_model;
using testing::split_file;

std::vector<uint32_t> roundtrip_faces(const std::vector<uint32_t>& faces, FaceOrder order = FaceOrder::Exact) {
  std::vector<uint8_t> bytes = encode_faces(faces, order);
  std::vector<uint32_t> back;
  std::string err;
  const uint32_t V = faces.empty() ? 0 : *std::max_element(faces.begin(), faces.end()) + 1;
  EXPECT_TRUE(decode_faces(bytes.data(), bytes.size(), V, &back, &err)) << err;
  return back;
}

// Each triangle as its rotation that starts with the smallest id, sorted: what a traversal
// layout must preserve (the triangles and their windings, not their order).
std::vector<std::array<uint32_t, 3>> canonical_triangles(const std::vector<uint32_t>& faces) {
  std::vector<std::array<uint32_t, 3>> tris;
  for (size_t t = 0; t + 2 < faces.size(); t += 3) {
    int r = 0;
    for (int k = 1; k < 3; ++k)
      if (faces[t + k] < faces[t + r]) r = k;
    tris.push_back({faces[t + r], faces[t + (r + 1) % 3], faces[t + (r + 2) % 3]});
  }
  std::sort(tris.begin(), tris.end());
  return tris;
}

TEST(FacesCodec, RoundTripsCorpusMeshesExactly) {
  if (!test::have_corpus_ext()) GTEST_SKIP() << "corpus-ext not found at " << DCURVE_CORPUS_EXT;
  const std::filesystem::path corpus = DCURVE_CORPUS_EXT;
  for (const char* seq : {"horse-gallop", "chicken-crossing", "elastic-cow", "cloth-sphere", "crane"}) {
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    std::string err;
    ASSERT_TRUE(read_mesh((corpus / seq / "frame_00000.obj").string(), &xyz, &faces, &err)) << err;
    EXPECT_EQ(roundtrip_faces(faces), faces) << seq;
    std::vector<uint32_t> traversal = roundtrip_faces(faces, FaceOrder::Traversal);
    EXPECT_EQ(canonical_triangles(traversal), canonical_triangles(faces)) << seq;
    // The writer knows the order without decoding: the list it reports is the decoded one.
    EXPECT_EQ(traversal_order(faces), traversal) << seq;
  }
}

TEST(FacesCodec, RoundTripsSoupsAndEdgeCases) {
  EXPECT_TRUE(roundtrip_faces({}).empty());
  const uint32_t big = UINT32_MAX - 1;
  std::vector<uint32_t> edge = {big, 0, big - 1, 5, 5, 5, 0, big, 7, 7, 1, 2, 0, 1, 2, 0, 1, 2};
  EXPECT_EQ(roundtrip_faces(edge), edge);
  std::mt19937 rng(7);
  for (int n : {1, 2, 17, 1000}) {
    std::vector<uint32_t> soup(size_t(n) * 3);
    for (auto& v : soup) v = rng() % (n < 100 ? 10 : 100000);
    EXPECT_EQ(roundtrip_faces(soup), soup);
    EXPECT_EQ(canonical_triangles(roundtrip_faces(soup, FaceOrder::Traversal)), canonical_triangles(soup));
    EXPECT_EQ(traversal_order(soup), roundtrip_faces(soup, FaceOrder::Traversal)) << n;
  }
  EXPECT_EQ(traversal_order(edge), roundtrip_faces(edge, FaceOrder::Traversal));
  EXPECT_EQ(canonical_triangles(roundtrip_faces(edge, FaceOrder::Traversal)), canonical_triangles(edge));
}

TEST(FacesCodec, RejectsEveryTruncationAndBadOps) {
  const Model m = small_model(3);
  std::vector<uint32_t> out;
  std::string err;
  for (FaceOrder order : {FaceOrder::Exact, FaceOrder::Traversal}) {
    std::vector<uint8_t> bytes = encode_faces(m.faces, order);
    for (size_t n = 0; n < bytes.size(); ++n) EXPECT_FALSE(decode_faces(bytes.data(), n, m.meta.vertex_count, &out, &err)) << n;
  }
  // An op that names an edge the history does not hold yet (first triangle).
  std::vector<uint8_t> bad = {0, 1, 0x80 | (3 << 3)};
  EXPECT_FALSE(decode_faces(bad.data(), bad.size(), m.meta.vertex_count, &out, &err));
  EXPECT_NE(err.find("edge"), std::string::npos) << err;
  bad = {0, 1, 0x40 | 7};  // reserved bits
  EXPECT_FALSE(decode_faces(bad.data(), bad.size(), m.meta.vertex_count, &out, &err));
  bad = {0, 200, 1};  // more triangles than bytes
  EXPECT_FALSE(decode_faces(bad.data(), bad.size(), m.meta.vertex_count, &out, &err));
  bad = {1, 1, 1, 2, 0, 2, 2};  // traversal symbol 2
  EXPECT_FALSE(decode_faces(bad.data(), bad.size(), m.meta.vertex_count, &out, &err));
  bad = {9, 0};  // unknown layout
  EXPECT_FALSE(decode_faces(bad.data(), bad.size(), m.meta.vertex_count, &out, &err));
  EXPECT_NE(err.find("layout"), std::string::npos) << err;
}

void expect_same(const Model& a, const Model& b) {
  EXPECT_EQ(a.meta.vertex_count, b.meta.vertex_count);
  EXPECT_EQ(a.meta.frame_count, b.meta.frame_count);
  EXPECT_EQ(a.meta.frame_rate, b.meta.frame_rate);
  EXPECT_EQ(a.meta.tolerance, b.meta.tolerance);
  EXPECT_EQ(a.meta.diag, b.meta.diag);
  EXPECT_EQ(a.meta.units, b.meta.units);
  EXPECT_EQ(a.curves.vertices, b.curves.vertices);
  EXPECT_EQ(a.curves.offsets, b.curves.offsets);
  EXPECT_EQ(a.curves.closed, b.curves.closed);
  ASSERT_EQ(a.curves.u.size(), b.curves.u.size());
  for (size_t i = 0; i < a.curves.u.size(); ++i) {
    EXPECT_NEAR(a.curves.u[i], b.curves.u[i], 0.5 / 65535) << i;
    EXPECT_EQ(quantize_curve_u(a.curves.u[i]), b.curves.u[i]) << i;
  }
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (size_t s = 0; s < a.segments.size(); ++s) {
    EXPECT_EQ(a.segments[s].first_frame, b.segments[s].first_frame);
    EXPECT_EQ(a.segments[s].last_frame, b.segments[s].last_frame);
    EXPECT_EQ(a.segments[s].mode, b.segments[s].mode);
    ASSERT_EQ(a.segments[s].motion.size(), b.segments[s].motion.size());
  }
  EXPECT_EQ(a.residual.step, b.residual.step);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(a.residual.origin[k], b.residual.origin[k]);
  EXPECT_EQ(a.residual.payload, b.residual.payload);
}

// CRC-32C against its published check value and a bit-at-a-time reference, through the
// instruction where the CPU has it and through the tables: the table loop folds sixteen bytes
// per step, so every length and start offset around that is checked.
TEST(Crc32c, MatchesTheCheckValueAndABitwiseReference) {
  const char* check = "123456789";
  EXPECT_EQ(crc32c(check, 9), 0xE3069283u);  // the CRC-32C check value (RFC 3720, B.4)
  EXPECT_EQ(crc32c(check, 0), 0u);
  EXPECT_EQ(crc32c_by_tables(check, 9), 0xE3069283u);
  auto bitwise = [](const uint8_t* p, size_t n, uint32_t seed) {
    uint32_t c = ~seed;
    for (size_t i = 0; i < n; ++i) {
      c ^= p[i];
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0x82F63B78u & (0u - (c & 1)));
    }
    return ~c;
  };
  std::mt19937 rng(7);
  std::vector<uint8_t> data(100);
  for (uint8_t& b : data) b = uint8_t(rng());
  for (size_t start = 0; start < 9; ++start)
    for (size_t n = 0; start + n <= data.size(); ++n) {
      ASSERT_EQ(crc32c(data.data() + start, n), bitwise(data.data() + start, n, 0)) << start << " " << n;
      ASSERT_EQ(crc32c_by_tables(data.data() + start, n), bitwise(data.data() + start, n, 0)) << start << " " << n;
      // Chaining through the seed equals one pass over the whole range.
      const size_t cut = n / 3;
      ASSERT_EQ(crc32c(data.data() + start + cut, n - cut, crc32c(data.data() + start, cut)),
                bitwise(data.data() + start, n, 0));
    }
}

// Long ranges, which the instruction path cuts into three lanes joined by shifts, against the
// tables: around the lanes' 6 KiB steps, at odd starts, chained through the seed.
TEST(Crc32c, LongRangesMatchTheTables) {
  std::mt19937 rng(9);
  std::vector<uint8_t> data(40000);
  for (uint8_t& b : data) b = uint8_t(rng());
  for (size_t n : {size_t(6143), size_t(6144), size_t(6145), size_t(12288), size_t(20000), size_t(39990)})
    for (size_t start : {size_t(0), size_t(3), size_t(7)}) {
      ASSERT_EQ(crc32c(data.data() + start, n), crc32c_by_tables(data.data() + start, n)) << start << " " << n;
      ASSERT_EQ(crc32c(data.data() + start, n, 0x12345678u), crc32c_by_tables(data.data() + start, n, 0x12345678u));
    }
}

TEST(Container, RoundTripPreservesEveryField) {
  const Model m = small_model(5, {0, 2, 4});
  std::vector<uint8_t> bytes = write_container(m);
  Model back;
  std::string err;
  std::vector<SectionInfo> infos;
  ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &back, &err, &infos)) << err;
  expect_same(m, back);
  EXPECT_EQ(back.faces, m.faces);
  ASSERT_EQ(infos.size(), 5u);
  EXPECT_EQ(infos[1].tag, "FACE");
  EXPECT_FALSE(infos[1].required);
  EXPECT_EQ(write_container(back), bytes);  // deterministic writer
}

// What the writer reports of each section is what a reader finds there: the encoder takes
// its section sizes from the writer instead of parsing its own output.
TEST(Container, WriterReportsTheSectionsAReaderFinds) {
  using Layout = WriteOptions::FaceLayout;
  Model sheet = testing::sheet_model(6, 4);
  sheet.faces = traversal_order(sheet.faces);
  const std::vector<std::pair<Model, Layout>> cases = {{small_model(5, {0, 2, 4}), Layout::Smallest},
                                                       {testing::without_faces(small_model(3)), Layout::Smallest},
                                                       {sheet, Layout::Traversal},
                                                       {sheet, Layout::Compact},
                                                       {sheet, Layout::Exact}};
  for (const auto& [model, layout] : cases) {
    WriteOptions o;
    o.face_layout = layout;
    std::vector<SectionInfo> written, found;
    const std::vector<uint8_t> bytes = write_container(model, o, &written);
    Model back;
    std::string err;
    ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &back, &err, &found)) << err;
    ASSERT_EQ(written.size(), found.size());
    for (size_t i = 0; i < found.size(); ++i) {
      const SectionInfo &w = written[i], &f = found[i];
      EXPECT_EQ(w.tag, f.tag);
      EXPECT_EQ(w.required, f.required) << f.tag;
      EXPECT_EQ(w.compressed, f.compressed) << f.tag;
      EXPECT_EQ(w.offset, f.offset) << f.tag;
      EXPECT_EQ(w.header_bytes, f.header_bytes) << f.tag;
      EXPECT_EQ(w.stored_bytes, f.stored_bytes) << f.tag;
      EXPECT_EQ(w.raw_bytes, f.raw_bytes) << f.tag;
      EXPECT_EQ(w.face_layout, f.face_layout) << f.tag;
    }
  }
}

// The writer never hands a reader other faces than model.faces: Traversal is used only for
// faces already in traversal order, and then when it is smaller.
TEST(Container, ReaderGetsTheModelFacesBack) {
  Model m = small_model(3);
  std::vector<uint32_t> strip;
  for (uint32_t v = 0; v + 2 < 6; ++v) strip.insert(strip.end(), {v, v + 1 + v % 2, v + 2 - v % 2});
  for (const std::vector<uint32_t>& faces : {m.faces, strip, traversal_order(strip), traversal_order(m.faces)}) {
    m.faces = faces;
    for (auto layout : {WriteOptions::FaceLayout::Smallest, WriteOptions::FaceLayout::Exact}) {
      WriteOptions opt;
      opt.face_layout = layout;
      std::vector<uint8_t> bytes = write_container(m, opt);
      Model back;
      std::string err;
      ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &back, &err)) << err;
      EXPECT_EQ(back.faces, faces);
    }
  }
}

TEST(Container, ConnectivityIsOptional) {
  const Model m = testing::without_faces(small_model(3));
  WriteOptions opt;
  opt.connectivity = false;
  std::vector<uint8_t> bytes = write_container(m, opt);
  Model back;
  std::string err;
  ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &back, &err)) << err;
  EXPECT_TRUE(back.faces.empty());
  expect_same(m, back);
  EXPECT_LT(bytes.size(), write_container(small_model(3)).size());
}

bool reads(const std::vector<uint8_t>& bytes, std::string* err) {
  Model m;
  return read_container(bytes.data(), bytes.size(), &m, err);
}

TEST(Container, RoomToGrow) {
  const std::vector<uint8_t> good = write_container(small_model(3));
  std::string err;
  RawFile f = split_file(good);
  ASSERT_TRUE(reads(assemble(f), &err)) << err;  // the test's own writer agrees with ours

  RawFile extra = f;
  extra.sections.insert(extra.sections.begin() + 2, plain_section("XTRA", false, {1, 2, 3}));
  EXPECT_TRUE(reads(assemble(extra), &err)) << "unknown optional sections are skipped: " << err;

  extra.sections[2].flags = 1;
  EXPECT_FALSE(reads(assemble(extra), &err));
  EXPECT_NE(err.find("unknown required section XTRA"), std::string::npos) << err;

  RawFile flagged = f;
  EXPECT_EQ(f.flags, kFileFlagZeroBlocks);  // 3.1's one feature flag, always written
  flagged.flags = 0;  // as 3.0 wrote it
  EXPECT_TRUE(reads(assemble(flagged), &err)) << err;
  flagged.flags = kFileFlagZeroBlocks | 0x10000;  // a hint bit
  EXPECT_TRUE(reads(assemble(flagged), &err)) << err;
  flagged.flags = 0x2;  // a required feature no decoder knows
  EXPECT_FALSE(reads(assemble(flagged), &err));

  RawFile minor = f;
  minor.minor = 7;
  EXPECT_TRUE(reads(assemble(minor), &err)) << err;
  RawFile major = f;
  major.major = kFormatVersionMajor + 1;
  EXPECT_FALSE(reads(assemble(major), &err));
  EXPECT_NE(err.find("version"), std::string::npos) << err;

  RawFile section_flag = f;
  section_flag.sections[0].flags |= 0x8;
  EXPECT_FALSE(reads(assemble(section_flag), &err));

  RawFile swapped = f;
  std::swap(swapped.sections[2], swapped.sections[3]);
  EXPECT_FALSE(reads(assemble(swapped), &err));
  EXPECT_NE(err.find("order"), std::string::npos) << err;

  RawFile missing = f;
  missing.sections.erase(missing.sections.begin());  // META
  EXPECT_FALSE(reads(assemble(missing), &err));
  EXPECT_NE(err.find("missing required section META"), std::string::npos) << err;
}

// Format 2.2: a file whose curves are one point per vertex and that has no segments
// carries neither CURV nor SEGS; a reader restores both, and still reads the explicit
// sections a 2.1 writer wrote for the same model.
TEST(Container, SingletonCurvesAndNoSegmentsNeedNoSections) {
  Model m = small_model(3);
  m.curves = singleton_curves(m.meta.vertex_count);
  m.residual.payload = encode_residuals(m, testing::grid(m.meta.vertex_count, 3));
  const std::vector<uint8_t> bytes = write_container(m);
  Model back;
  std::string err;
  std::vector<SectionInfo> infos;
  ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &back, &err, &infos)) << err;
  for (const SectionInfo& s : infos) EXPECT_TRUE(s.tag != "CURV" && s.tag != "SEGS") << s.tag;
  expect_same(m, back);
  EXPECT_TRUE(is_singleton_curves(back.curves, m.meta.vertex_count));

  // The same model with the two sections written out, as 2.1 wrote it.
  RawFile f = split_file(bytes);
  ByteWriter curv;
  curv.u32(m.meta.vertex_count);
  for (uint32_t v = 0; v < m.meta.vertex_count; ++v) curv.varint(2);  // length 1, open
  curv.varint(0);
  for (uint32_t v = 1; v < m.meta.vertex_count; ++v) curv.varint(2);  // id delta +1
  for (uint32_t v = 0; v < m.meta.vertex_count; ++v) curv.u16(0);
  f.sections.insert(f.sections.begin() + 2, plain_section("CURV", true, curv.data()));
  f.sections.insert(f.sections.begin() + 3, plain_section("SEGS", true, {0, 0, 0, 0}));
  Model explicit_back;
  ASSERT_TRUE(read_container(assemble(f).data(), assemble(f).size(), &explicit_back, &err)) << err;
  expect_same(back, explicit_back);
  EXPECT_GT(assemble(f).size(), bytes.size() + 20);

  // Curves other than one point per vertex still need CURV: a file without it is read with
  // singleton curves, which then cannot match a SEGS section sized for two curves.
  const std::vector<uint8_t> two_curves = write_container(small_model(3, {0, 2}));
  RawFile g = split_file(two_curves);
  ASSERT_EQ(g.sections[2].tag, "CURV");
  g.sections.erase(g.sections.begin() + 2);
  EXPECT_FALSE(reads(assemble(g), &err));
  EXPECT_NE(err.find("SEGS"), std::string::npos) << err;
}

TEST(Container, RejectsEveryTruncation) {
  const std::vector<uint8_t> bytes = write_container(small_model(3, {0, 2}));
  for (size_t n = 0; n < bytes.size(); ++n) {
    std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + n);
    std::string err;
    EXPECT_FALSE(reads(cut, &err)) << n;
    EXPECT_FALSE(err.empty()) << n;
  }
}

TEST(Container, DetectsEverySingleByteFlip) {
  const std::vector<uint8_t> bytes = write_container(small_model(3, {0, 2}));
  for (size_t i = 0; i < bytes.size(); ++i)
    for (uint8_t mask : {uint8_t(0x01), uint8_t(0x80), uint8_t(0xff)}) {
      std::vector<uint8_t> bad = bytes;
      bad[i] ^= mask;
      std::string err;
      EXPECT_FALSE(reads(bad, &err)) << "byte " << i << " mask " << int(mask);
    }
}

TEST(Container, RejectsRandomFiles) {
  std::mt19937 rng(11);
  const std::vector<uint8_t> good = write_container(small_model(3));
  for (int i = 0; i < 3000; ++i) {
    std::vector<uint8_t> bytes(rng() % 300);
    for (auto& b : bytes) b = uint8_t(rng());
    if (i % 2 && bytes.size() >= 20) {
      // A valid header in front of random sections reaches the section parser.
      std::copy(good.begin(), good.begin() + 20, bytes.begin());
    }
    std::string err;
    EXPECT_FALSE(reads(bytes, &err));
  }
}

// Files whose checksums are right but whose counts are absurd must fail on the count, not
// on an allocation (the sanitizer build aborts on a huge allocation).
TEST(Container, RejectsAbsurdCountsWithValidChecksums) {
  const RawFile f = split_file(write_container(small_model(3, {0, 2})));  // all five sections
  ASSERT_EQ(f.sections.size(), 5u);
  auto with_section = [&](size_t index, const std::vector<uint8_t>& raw) {
    RawFile g = f;
    g.sections[index] = plain_section(g.sections[index].tag, index != 1, raw);
    return assemble(g);
  };
  std::string err;
  ByteWriter meta;
  meta.u32(0xffffffffu);
  meta.u32(0xffffffffu);
  meta.f64(30);
  meta.f64(1e-3);
  meta.f64(1);
  meta.str("");
  EXPECT_FALSE(reads(with_section(0, meta.data()), &err));
  EXPECT_NE(err.find("implausible"), std::string::npos) << err;
  // Without CURV the one-point curves would be V long: the bound comes first.
  RawFile no_curves = f;
  no_curves.sections.erase(no_curves.sections.begin() + 2, no_curves.sections.begin() + 4);
  no_curves.sections[0] = plain_section("META", true, meta.data());
  EXPECT_FALSE(reads(assemble(no_curves), &err));
  EXPECT_NE(err.find("implausible"), std::string::npos) << err;
  // F = 0 (invalid, but only found later) with a billion vertices: found by the fuzzer, which
  // saw the one-point curves allocated before the bound applied.
  ByteWriter no_frames;
  no_frames.u32(1000000000u);
  no_frames.u32(0);
  no_frames.f64(30);
  no_frames.f64(1e-3);
  no_frames.f64(1);
  no_frames.str("");
  no_curves.sections[0] = plain_section("META", true, no_frames.data());
  EXPECT_FALSE(reads(assemble(no_curves), &err));
  EXPECT_NE(err.find("implausible"), std::string::npos) << err;

  ByteWriter faces;
  faces.varint(uint64_t(1) << 40);
  EXPECT_FALSE(reads(with_section(1, faces.data()), &err));

  ByteWriter curves;
  curves.u32(0xffffffffu);
  curves.varint(uint64_t(0xffffffffu) << 1);
  EXPECT_FALSE(reads(with_section(2, curves.data()), &err));

  ByteWriter segs;
  segs.u32(0xffffffffu);
  EXPECT_FALSE(reads(with_section(3, segs.data()), &err));

  ByteWriter resi;
  resi.f64(0.25);
  for (int k = 0; k < 3; ++k) resi.f64(0);
  resi.varint(uint64_t(1) << 60);
  EXPECT_FALSE(reads(with_section(4, resi.data()), &err));

  RawFile huge = f;  // a compressed section that claims to expand to 1 TB
  huge.sections[2].flags |= 2;
  huge.sections[2].raw_size = uint64_t(1) << 40;
  EXPECT_FALSE(reads(assemble(huge), &err));
  EXPECT_NE(err.find("implausible"), std::string::npos) << err;
}

}  // namespace
}  // namespace dcurve
