#include <cstdio>
#include <filesystem>

#include "bench/inbetween_bench.h"
#include "bench/paper2024_faithful.h"
#include "bench/plot.h"
#include "bench/report.h"
#include "bench/runner.h"
#include "cli/commands.h"
#include "cli/number_range.h"
#include "cli/progress.h"
#include "bench/paper_protocols.h"
#include "encoder/curves/extract.h"
#include "corpus/input.h"
#include "encoder/io/files.h"
#include "encoder/io/output_file.h"
#include "corpus/sim/scene.h"

namespace dcurve::cli {
namespace {

// The label a result carries: the folder's own name.
std::string input_name(const std::string& path) {
  std::filesystem::path p(path);
  if (!p.has_filename()) p = p.parent_path();
  return p.filename().string();
}

// One bench input: a frame folder, a scene file or a built-in scene name (simulated here).
bool load_input(const std::string& arg, std::string* name, Animation* anim, std::string* error) {
  *name = input_name(arg);
  return load_animation_input(arg, true, progress_bar(input_stage_label(arg)), anim, error);
}

// The 2024 protocol as the paper describes it (bench/paper2024_faithful.h) and the honest one
// on the same full-length lines, when the input has lines along an axis (the rope's).
bool add_faithful_2024(const Animation& anim, nlohmann::json* result, std::string* table, std::string* error) {
  Curves lines;
  std::string why;
  if (!surface_lines(anim, &lines, &why)) {
    (*result)["faithful"] = nullptr;
    if (table) *table += "(no full-length lines along an axis: " + why + ")\n";
    return true;
  }
  nlohmann::json faithful, honest;
  std::string faithful_table, honest_table;
  if (!run_paper2024_faithful(anim, lines, &faithful, table ? &faithful_table : nullptr, error, true) ||
      !run_paper_protocol("paper2024", anim, lines, &honest, table ? &honest_table : nullptr, error, true))
    return false;
  (*result)["faithful"] = faithful;
  (*result)["honest_on_lines"] = honest;
  if (table) *table += "\n" + faithful_table + "\nThe honest protocol on the same lines:\n" + honest_table;
  return true;
}

// The papers' own protocols (bench/paper_protocols.h) on each input, with curves extracted
// from frame 0 as the encoder would.
template <class Opts>
int run_protocol(const Opts& o, const std::string& protocol) {
  if (o.inputs.empty()) {
    std::fprintf(stderr, "dcurve bench: --protocol needs an input\n");
    return 2;
  }
  nlohmann::json all = nlohmann::json::array();
  for (const auto& arg : o.inputs) {
    std::string name, err, table;
    Animation anim;
    Curves curves;
    nlohmann::json result;
    if (!load_input(arg, &name, &anim, &err) ||
        !extract_curves(anim.frames[0], anim.vertex_count, anim.faces, CurveOptions{}, &curves, &err) ||
        !run_paper_protocol(protocol, anim, curves, &result, o.json ? nullptr : &table, &err, true)) {
      std::fprintf(stderr, "dcurve bench: %s: %s\n", arg.c_str(), err.c_str());
      return 1;
    }
    result["input"] = name;
    if (protocol == "paper2024" && !add_faithful_2024(anim, &result, o.json ? nullptr : &table, &err)) {
      std::fprintf(stderr, "dcurve bench: %s: %s\n", arg.c_str(), err.c_str());
      return 1;
    }
    all.push_back(result);
    if (!o.json) std::printf("%s: %s\n%s\n", name.c_str(), protocol.c_str(), table.c_str());
  }
  if (o.json) std::printf("%s\n", (all.size() == 1 ? all[0] : all).dump().c_str());
  return 0;
}

// In-between errors at held-out odd frames (bench/inbetween_bench.h) of each input.
template <class Opts>
int run_inbetween(const Opts& o) {
  EncodeOptions eo;
  eo.tolerance = o.tolerances.empty() ? 1e-3 : o.tolerances[0];
  eo.effort = o.effort;
  eo.grid_refinement = o.grid;
  // An input that fails is reported and skipped: the others' rows are still printed, and
  // the exit status says that one failed.
  std::vector<bench::InbetweenResult> results;
  int status = 0;
  for (const auto& arg : o.inputs) {
    std::string name, err;
    Animation anim;
    bench::InbetweenResult r;
    if (!load_input(arg, &name, &anim, &err)) {
      std::fprintf(stderr, "dcurve bench: %s\n", err.c_str());
      status = 1;
      continue;
    }
    if (o.max_frames > 0 && anim.frames.size() > o.max_frames) anim.frames.resize(o.max_frames);
    if (!bench::run_inbetween_bench(name, anim, eo, o.with_pde, &r, &err)) {
      std::fprintf(stderr, "dcurve bench: %s: %s\n", arg.c_str(), err.c_str());
      status = 1;
      continue;
    }
    results.push_back(r);
  }
  if (o.json)
    std::printf("%s\n", bench::inbetween_json(results).dump().c_str());
  else
    std::printf("%s", bench::inbetween_table(results).c_str());
  return status;
}

bool write_text(const std::string& path, const std::string& text) {
  std::string err;
  if (write_file_atomic(path, text.data(), text.size(), &err)) return true;
  std::fprintf(stderr, "dcurve bench: %s\n", err.c_str());
  return false;
}

}  // namespace

Action add_bench(CLI::App& app) {
  struct Opts {
    std::vector<std::string> inputs, methods;
    std::vector<double> tolerances;
    std::string csv, plot, protocol;
    bool json = false;
    uint32_t max_frames = 0;
    int effort = EncodeOptions().effort;
    bool inbetween = false, with_pde = false;
    double grid = 0;
  };
  auto o = std::make_shared<Opts>();
  app.add_option("inputs", o->inputs, "Frame folders, scene files or built-in scene names (none: built-in corpus)");
  app.add_option("--tolerance", o->tolerances,
                 "Max error, fraction of the rest-pose bounding-box diagonal; repeat for several (default 1e-3)")
      ->check(finite_range(kMinTolerance, 0.5))
      ->allow_extra_args(false);
  app.add_option("--methods", o->methods, "Comma-separated subset of methods (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember(bench::all_methods()));
  app.add_option("--frames", o->max_frames, "Use only the first N frames of each input (0 = all)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--effort", o->effort,
                 "dcurve's encode effort (as dcurve encode --effort): 2 tries two residual grids side by side, "
                 "1 encodes once, 3 walks the grids by trial encodes; lower is faster")
      ->check(CLI::Range(kMinEffort, kMaxEffort))
      ->capture_default_str();
  app.add_flag("--json", o->json, "Print one JSON object on stdout instead of the table");
  app.add_option("--csv", o->csv, "Also write the results as CSV to this file");
  app.add_option("--plot", o->plot, "Also write the rate-distortion plot (SVG) to this file");
  app.add_option("--protocol", o->protocol, "Run a paper's own protocol instead of the comparison")
      ->check(CLI::IsMember({"paper2024", "paper2022"}));
  app.add_flag("--inbetween", o->inbetween,
               "Instead of the comparison: encode each input's even frames, decode at the odd frames' times and "
               "print the in-between RMSE of every rule, of the rule the file records, and of the rules through "
               "the true even frames (first --tolerance only)");
  app.add_flag("--with-pde", o->with_pde, "With --inbetween: also a file with a PDE model whose motions are all kept");
  app.add_option("--grid", o->grid,
                 "With --inbetween: dcurve's residual grid (as dcurve encode --grid; 0 = auto, 1..16 skips the trials)")
      ->check(CLI::Range(0.0, 16.0));
  return [o]() {
    if (!o->protocol.empty()) return run_protocol(*o, o->protocol);
    if (o->inputs.empty()) {
      // The built-in corpus; the full-size rope (20k vertices) only when named, it takes minutes.
      for (const auto& n : builtin_scene_names())
        if (n != "rope") o->inputs.push_back(n);
    }
    if (o->inbetween) return run_inbetween(*o);
    if (o->tolerances.empty()) o->tolerances = {1e-3};
    std::vector<std::pair<std::string, Animation>> inputs;
    for (const auto& arg : o->inputs) {
      std::string name, err;
      Animation anim;
      if (!load_input(arg, &name, &anim, &err)) {
        std::fprintf(stderr, "dcurve bench: %s\n", err.c_str());
        return 1;
      }
      if (o->max_frames > 0 && anim.frames.size() > o->max_frames) anim.frames.resize(o->max_frames);
      inputs.emplace_back(name, std::move(anim));
    }
    std::vector<bench::InputResult> results;
    for (const auto& [name, anim] : inputs)
      for (double tol : o->tolerances) {
        char label[64];
        std::snprintf(label, sizeof label, "%.12s %g", name.c_str(), tol);
        results.push_back(bench::run_bench(name, anim, tol, o->methods, progress_bar(label), o->effort));
      }
    if (o->json)
      std::printf("%s\n", bench::results_json(results).dump().c_str());
    else
      std::printf("%s", bench::format_table(results).c_str());
    if (!o->csv.empty() && !write_text(o->csv, bench::results_csv(results))) return 1;
    if (!o->plot.empty() && !write_text(o->plot, bench::rate_distortion_svg(results))) return 1;
    return 0;
  };
}

}  // namespace dcurve::cli
