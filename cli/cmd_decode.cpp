#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/number_range.h"
#include "decoder/dcurve.hpp"
#include "encoder/io/frames.h"

namespace dcurve::cli {

Action add_decode(CLI::App& app) {
  struct Opts {
    std::string input, output, format = "obj";
    int frames = 0;
    double t = -1;
  };
  auto o = std::make_shared<Opts>();
  app.add_option("input", o->input, ".dcrv file")->required();
  app.add_option("-o,--output", o->output, "Output folder (frame_00000.obj, ...)")->required();
  auto* frames = app.add_option("--frames", o->frames, "Write N frames at t = i/(N-1) (default: the stored frame count)")
                     ->check(CLI::Range(1, 1000000));
  auto* t = app.add_option("--t", o->t, "Write one mesh at time T in [0,1]")->check(finite_range(0.0, 1.0));
  frames->excludes(t);
  app.add_option("--format", o->format, "Mesh format")->check(CLI::IsMember({"obj", "ply"}))->capture_default_str();
  return [o]() {
    std::string err;
    auto dec = Decoder::open_file(o->input, &err);
    if (!dec) {
      std::fprintf(stderr, "dcurve decode: %s\n", err.c_str());
      return 1;
    }
    Animation out;
    out.vertex_count = dec->vertex_count();
    if (dec->faces()) out.faces.assign(dec->faces(), dec->faces() + 3 * size_t(dec->face_count()));
    std::vector<double> times;
    if (o->t >= 0) {
      times.push_back(o->t);
    } else {
      int n = o->frames > 0 ? o->frames : int(dec->frame_count());
      for (int i = 0; i < n; ++i) times.push_back(n > 1 ? double(i) / (n - 1) : 0.0);
    }
    Error e;
    for (double tt : times) {
      out.frames.emplace_back(size_t(out.vertex_count) * 3);
      if (!dec->evaluate(tt, out.frames.back().data(), &e)) {
        std::fprintf(stderr, "dcurve decode: %s: %s\n", o->input.c_str(), e.message.c_str());
        return 1;
      }
    }
    if (!write_frame_folder(o->output, out, o->format, &err)) {
      std::fprintf(stderr, "dcurve decode: %s\n", err.c_str());
      return 1;
    }
    return 0;
  };
}

}  // namespace dcurve::cli
