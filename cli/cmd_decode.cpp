#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli/commands.h"
#include "cli/frame_output.h"
#include "cli/output_path.h"
#include "cli/messages.h"
#include "codec/common/error.h"
#include "codec/common/inbetween.h"
#include "codec/common/render_mesh.h"
#include "encoder/io/files.h"
#include "encoder/io/json_depth.h"
#include "encoder/io/obj_corners.h"
#include "decoder/dcurve.hpp"

namespace dcurve::cli {
namespace {

struct DecodeOpts {
  std::string input, output, format = "obj", interp = "file";
  int frames = 0;
  double t = -1, seconds = -1;
  bool force = false;
  OutputKind kind = OutputKind::Folder;
};

// The times to decode: --t, --time (seconds from frame 0), or N frames spread over [0, 1].
bool decode_times(const DecodeOpts& o, const Decoder& dec, std::vector<double>* times, std::string* error) {
  const uint32_t stored = dec.frame_count();
  if (o.seconds >= 0) {
    const double duration = stored > 1 && dec.frame_rate() > 0 ? (stored - 1) / dec.frame_rate() : 0;
    if (duration <= 0) return fail(error, o.input + ": holds no frame rate or a single frame; use --t");
    if (o.seconds > duration * (1 + 1e-9))
      return fail(error, o.input + ": --time " + std::to_string(o.seconds) + " s is past its end, " +
                             std::to_string(duration) + " s");
    times->push_back(std::min(1.0, o.seconds / duration));
  } else if (o.t >= 0) {
    times->push_back(o.t);
  } else {
    const uint32_t n = o.frames > 0 ? uint32_t(o.frames) : stored;
    times->reserve(n);
    for (uint32_t i = 0; i < n; ++i) times->push_back(n > 1 ? double(i) / (n - 1) : 0.0);
  }
  return true;
}

// One primitive per face group with its material; the materials' JSON and images as stored.
void describe_materials(const Decoder& dec, GltfScene* scene) {
  for (uint32_t g = 0; g < dec.group_count(); ++g) {
    const Group group = dec.group(g);
    scene->group_faces.push_back(group.face_count);
    scene->group_materials.push_back(group.material);
  }
  scene->materials_json = dec.materials_json();
  for (uint32_t i = 0; i < dec.image_count(); ++i) {
    size_t size = 0;
    const uint8_t* bytes = dec.image(i, &size);
    scene->images.push_back({dec.image_mime_type(i), std::vector<uint8_t>(bytes, bytes + size)});
  }
}

// glTF output draws render vertices: seam copies share their vertex's position, with the
// file's UVs and colours, its placement, and normals per frame (smooth across UV seams).
void describe_render_output(const Decoder& dec, OutputSpec* spec) {
  GltfScene& scene = spec->gltf;
  scene.placement.start_time = dec.start_time();
  scene.placement.has_matrix = dec.world_matrix(scene.placement.matrix);
  scene.placement.mesh_name = dec.mesh_name();
  scene.placement.node_name = dec.node_name();
  scene.normals = dec.face_count() > 0;
  spec->vertex_count = dec.render_vertex_count();
  const uint32_t* faces = dec.group_faces() ? dec.group_faces() : dec.render_faces();
  if (faces) spec->faces.assign(faces, faces + 3 * size_t(dec.face_count()));
  describe_materials(dec, &scene);
  for (Attribute a : {Attribute::TexCoord0, Attribute::TexCoord1, Attribute::Color0}) {
    const uint32_t n = dec.attribute_components(a);
    if (n == 0) continue;
    const float* v = dec.attribute(a);
    scene.attributes.push_back({attribute_gltf_name(AttributeSemantic(int(a))), n,
                                std::vector<float>(v, v + size_t(n) * spec->vertex_count)});
  }
}

// OBJ output keeps vertex i as vertex i and adds what the file has of UVs, normals (per
// render vertex, per frame) and material groups, with the OBJ's material library.
void describe_obj_output(const Decoder& dec, OutputSpec* spec) {
  if (!dec.render_source() || dec.face_count() == 0) return;
  ObjRender& obj = spec->obj;
  const size_t R = dec.render_vertex_count();
  obj.source.assign(dec.render_source(), dec.render_source() + R);
  const uint32_t* faces = dec.group_faces() ? dec.group_faces() : dec.render_faces();
  obj.corners.assign(faces, faces + 3 * size_t(dec.face_count()));
  if (dec.uvs()) obj.uv.assign(dec.uvs(), dec.uvs() + 2 * R);
  for (uint32_t g = 0; g < dec.group_count(); ++g) {
    obj.group_faces.push_back(dec.group(g).face_count);
    obj.group_names.push_back(dec.group_name(g));
  }
  obj.material_library = obj_material_library(dec.materials_json());
}

bool obj_output(const DecodeOpts& o) {
  return (o.kind == OutputKind::Mesh && lowercase_extension(o.output) == ".obj") ||
         (o.kind == OutputKind::Folder && o.format == "obj");
}

// glTF and OBJ outputs parse the materials' JSON (MATL): one nested deeper than any glTF is
// refused before a copy or dump of it can overflow the stack.
bool check_materials(const DecodeOpts& o, const Decoder& dec, std::string* error) {
  if (o.kind != OutputKind::Gltf && !obj_output(o)) return true;
  const std::string& json = dec.materials_json();
  return check_json_depth(json.data(), json.size(), kMaxJsonDepth, error) ||
         fail(error, o.input + ": its materials (MATL): " + *error);
}

OutputSpec output_spec(const DecodeOpts& o, const Decoder& dec, uint32_t frames) {
  OutputSpec spec;
  spec.path = o.output;
  spec.kind = o.kind;
  spec.inputs = {o.input};
  spec.folder_format = o.format;
  spec.force = o.force;
  spec.vertex_count = dec.vertex_count();
  if (dec.faces()) spec.faces.assign(dec.faces(), dec.faces() + 3 * size_t(dec.face_count()));
  spec.frame_count = frames;
  // Frames at i/(N-1) of the clip: the rate that keeps the clip's duration.
  const double duration = dec.frame_count() > 1 && dec.frame_rate() > 0 ? (dec.frame_count() - 1) / dec.frame_rate() : 0;
  spec.frame_rate = frames > 1 && duration > 0 ? (frames - 1) / duration : dec.frame_rate();
  spec.start_time = dec.start_time();
  if (o.kind == OutputKind::Gltf) describe_render_output(dec, &spec);
  if (obj_output(o)) describe_obj_output(dec, &spec);
  return spec;
}

// Decodes and writes one frame at a time: memory holds one frame whatever the count.
int run_decode(const DecodeOpts& o, const Messages& msg) {
  std::string err;
  auto dec = Decoder::open_file(o.input, &err);
  if (!dec) return msg.error(err);
  std::vector<double> times;
  if (!decode_times(o, *dec, &times, &err) || !check_materials(o, *dec, &err)) return msg.error(err);
  const OutputSpec spec = output_spec(o, *dec, uint32_t(times.size()));
  const bool spec_obj_empty = spec.obj.empty();
  auto sink = open_output(spec, &err);
  if (!sink) return msg.error(err);
  std::vector<float> xyz(size_t(dec->vertex_count()) * 3);
  const bool render = o.kind == OutputKind::Gltf, obj = !spec_obj_empty;
  std::vector<float> render_xyz, normals;
  if (render) render_xyz.resize(size_t(dec->render_vertex_count()) * 3);
  if ((render || obj) && dec->face_count() > 0) normals.resize(size_t(dec->render_vertex_count()) * 3);
  auto cursor = dec->make_cursor();
  Inbetween rule;
  if (inbetween_from_name(o.interp.c_str(), &rule)) cursor->set_interpolation(Interpolation(int(rule)));
  auto progress = msg.progress("decode");
  for (size_t i = 0; i < times.size(); ++i) {
    Error e;
    if (!cursor->evaluate(times[i], xyz.data(), &e)) return msg.error(o.input + ": " + e.message);
    if (render) dec->render_positions(xyz.data(), render_xyz.data());
    if (!normals.empty()) dec->compute_render_normals(xyz.data(), normals.data());
    const float* out = render ? render_xyz.data() : xyz.data();
    if (!sink->add(uint32_t(i), out, normals.empty() ? nullptr : normals.data(), &err)) return msg.error(err);
    if (progress) progress(double(i + 1) / double(times.size()));
  }
  if (!sink->finish(&err)) return msg.error(err);
  msg.detail("wrote " + std::to_string(times.size()) + " frame(s) of " + std::to_string(dec->vertex_count()) +
             " vertices to " + o.output);
  return 0;
}

}  // namespace

Action add_decode(CLI::App& app) {
  auto o = std::make_shared<DecodeOpts>();
  auto msg = std::make_shared<Messages>("decode");
  app.add_option("input", o->input, ".dcrv file")->required();
  app.add_option("-o,--output", o->output,
                 "Output: a folder (a name ending in / or without extension: frame_00000.obj, ...), one mesh "
                 "(.obj/.ply/.off, with --t or --time), a glTF file (.glb/.gltf: morph targets and a weights "
                 "animation) or a point cache (.pc2/.mdd)")
      ->required();
  auto* frames = app.add_option("--frames", o->frames, "Write N frames at t = i/(N-1) (default: the stored frame count)")
                     ->check(CLI::Range(1, 1000000));
  auto* t = app.add_option("--t", o->t, "Write one mesh at time T in [0,1]")->check(CLI::Range(0.0, 1.0));
  auto* seconds = app.add_option("--time", o->seconds, "Write one mesh at SECONDS from the first frame (at the file's frame rate)")
                      ->check(CLI::NonNegativeNumber);
  frames->excludes(t)->excludes(seconds);
  t->excludes(seconds);
  app.add_option("--format", o->format, "Frame format in a folder output")->check(CLI::IsMember({"obj", "ply"}))->capture_default_str();
  app.add_option("--interp", o->interp,
                 "Between stored frames: file (the rule the file records), linear, catmull-rom or hermite4 "
                 "(cubics through the neighbouring frames). A PDE model the file carries is followed by every "
                 "rule; stored frames decode the same under all")
      ->check(CLI::IsMember({"file", "linear", "catmull-rom", "hermite4"}))
      ->capture_default_str();
  app.add_flag("--force", o->force,
               "Replace an existing output file, or the frames (.obj/.ply/.off files) of an output folder, once the "
               "new output is complete");
  msg->add_flags(app);
  return [o, msg]() {
    if (!std::isfinite(o->seconds) || !std::isfinite(o->t)) {  // CLI11's range checks let "nan" through
      std::fprintf(stderr, "dcurve decode: --t and --time must be numbers\n");
      return 2;
    }
    std::string err;
    if (!output_kind(o->output, frame_output_kinds(), &o->kind, &err)) return msg->error(err);
    const bool one_mesh = o->kind == OutputKind::Mesh;
    if (one_mesh && o->t < 0 && o->seconds < 0 && o->frames != 1) {
      std::fprintf(stderr, "dcurve decode: %s is one mesh: choose its time with --t T or --time SECONDS\n", o->output.c_str());
      return 2;
    }
    return run_decode(*o, *msg);
  };
}

}  // namespace dcurve::cli
