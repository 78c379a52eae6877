#include "encoder/encoder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <memory>
#include <optional>

#include "codec/common/error.h"
#include "codec/common/model.h"
#include "codec/common/residual.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/model_prediction.h"
#include "decoder/dcurve.hpp"
#include "encoder/curves/extract.h"
#include "encoder/curves/report.h"
#include "encoder/face_order.h"
#include "encoder/render_attributes.h"
#include "encoder/render_limits.h"
#include "encoder/work_meter.h"
#include "encoder/rate/block_flags.h"
#include "encoder/rate/fast_grid.h"
#include "encoder/rate/fast_low_rank.h"
#include "encoder/rate/fast_plan.h"
#include "encoder/rate/inbetween_choice.h"
#include "encoder/rate/chunk_choice.h"
#include "encoder/rate/encode_context.h"
#include "encoder/rate/grid.h"
#include "encoder/rate/low_rank_choice.h"
#include "encoder/rate/motion_alternatives.h"
#include "encoder/rate/motion_choice.h"
#include "encoder/rate/motion_model.h"
#include "encoder/rate/residual_plan.h"
#include "encoder/rate/weights_store.h"

namespace dcurve {
namespace {

// Grid trials of --effort 3's walk on most inputs, for the progress forecast.
constexpr uint64_t kWalkTrials = 4;

// What the decoder's float32 output can add to a vertex's error: a few roundings of the
// largest coordinate.
double float_output_error(const Animation& anim) {
  double largest = 0;
  for (const auto& frame : anim.frames)
    for (float x : frame) largest = std::max(largest, double(std::fabs(x)));
  return 4.0 * std::sqrt(3.0) * largest * std::ldexp(1.0, -24);
}

// How far the residual layer may move a grid value from the input: the tolerance, less what
// the decoder's float32 output can add.
double snap_distance(const Animation& anim, double max_distance) { return max_distance - float_output_error(anim); }

// Decodes `bytes` with the runtime decoder at every input frame time and measures it: the
// only error figure the encoder reports.
bool measure_decoded(const std::vector<uint8_t>& bytes, const Animation& anim, ErrorStats* stats,
                     std::string* error) {
  std::string derr;
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &derr);
  if (!dec) return fail(error, "internal error: written file does not decode: " + derr);
  const uint32_t F = uint32_t(anim.frames.size());
  std::vector<std::vector<float>> decoded(F, std::vector<float>(size_t(anim.vertex_count) * 3));
  for (uint32_t f = 0; f < F; ++f) dec->evaluate(F > 1 ? double(f) / (F - 1) : 0.0, decoded[f].data());
  *stats = measure_error(anim, decoded);
  return true;
}

// The file's curves: extracted when a motion model or a file without faces reads them;
// otherwise one-vertex curves, which cost a few bytes where the extracted ones can take a
// large share of the file. Extraction failing (non-manifold input) also gives one-vertex
// curves.
Curves file_curves(const Animation& anim, const EncodeOptions& opt, std::string* fallback) {
  if (opt.model == ModelChoice::None && opt.connectivity) return singleton_curves(anim.vertex_count);
  CurveOptions co;
  co.target_points = opt.curve_points;
  Curves curves;
  if (!extract_curves(anim.frames[0], anim.vertex_count, anim.faces, co, &curves, fallback))
    return singleton_curves(anim.vertex_count);
  fallback->clear();
  return curves;
}

// What both encodes share: metadata, faces, the plain file's curves, the residual grid and
// its rounded values, the spatial weight tables its walks solved, and the plain file's
// traversal (it depends on the faces or curves alone, so the trials need not each build
// it again; the decodes of written files still build their own).
struct GridStart {
  Model model;
  std::vector<int32_t> rounded;
  double snap = 0;
  SpatialWeightsSource* weights = nullptr;
  std::shared_ptr<const Traversal> traversal;
  WorkMeter* meter = nullptr;  // counts the frames every plan of the encode plans; may be null
};

// The rate control's view of an encode of `anim` from `start`. Every effort searches all the
// coding orders: hierarchical orders interpolate smooth motion, and time order alone codes
// long, smooth clips much larger, though it changes little on others.
EncodeContext context_of(const Animation& anim, const EncodeOptions& opt, const GridStart& start) {
  EncodeContext c(anim.frames, start.rounded);
  c.snap_distance = start.snap;
  c.shared.weights_source = start.weights;
  c.shared.traversal = start.traversal.get();
  c.plan.threads = opt.threads;
  c.plan.meter = start.meter;
  c.plan.try_geometry_per_frame = opt.effort == kMaxEffort;
  c.write.connectivity = opt.connectivity;
  return c;
}

// The encode without a PDE model (encode_plain): the file's model and what its payloads
// code, and the same before the low-rank choice, the residual layer alone: what a PDE motion
// competes with inside a file, which cannot also carry a low-rank model.
struct PlainEncode {
  Model model;
  CodedResidual coded;
  Model residual_only;
  CodedPayload residual_only_coded;
  LowRankPick low_rank;  // the low-rank model kept, none when components is 0
};

// What a grid trial of part of the clip chose, for the whole clip's plain encode to follow
// instead of searching again: the coding order and cluster layout, the low-rank model.
struct TrialChoices {
  PredictorPlan plan;  // the trial's plan, for narrow_to_plan
  LowRankPick low_rank;
};

// The residual layer alone, then a low-rank model where it pays, into *out. `bytes` (may be
// null) receives the whole file's size, as the low-rank choice measured it.
// follow (may be null): what a grid trial chose, planned and tried instead of the searches.
bool encode_plain(const Animation& anim, const EncodeOptions& opt, const GridStart& start, PlainEncode* out,
                  std::string* error, uint64_t* bytes = nullptr, const TrialChoices* follow = nullptr) {
  Model* m = &out->model;
  *m = start.model;
  EncodeContext context = context_of(anim, opt, start);
  if (follow) context.plan = narrow_to_plan(context.plan, follow->plan);
  std::vector<int32_t> q = start.rounded;
  ResidualPlan plan = choose_chunked_plan(*m, anim.frames, start.snap, &q, context.shared, context.plan);
  m->residual.payload = encode_residuals(*m, q, plan, context.shared);
  if (m->residual.payload.empty()) return fail(error, "internal error: the residual plan is invalid");
  out->residual_only = *m;
  out->residual_only_coded = {plan, q};
  LowRankChoiceOptions lro;
  // The fast profile chooses its own low-rank model (fast_low_rank.h) on the grid found here.
  lro.components = opt.profile == Profile::Fast && opt.low_rank == -1 ? 0 : opt.low_rank;
  lro.first_frame_anchor = opt.low_rank_first_frame;
  lro.posed_anchors = opt.low_rank_poses;
  // A part without a model says little of the whole clip, whose drift a component may carry.
  if (follow && lro.components == -1 && follow->low_rank.components > 0) lro.follow = &follow->low_rank;
  LowRankChoiceReport rep;
  if (!choose_low_rank(m, {plan, q}, context, lro, &rep, error, &out->coded)) return false;
  out->low_rank = rep.kept;
  if (rep.kept.components == 0) out->coded = {{std::move(plan), std::move(q)}, {}, {}};
  if (bytes) *bytes = rep.bytes;
  return true;
}

// What every file of `anim` holds before its grid: metadata, faces, and the curves of a
// file without a PDE model.
Model file_base(const Animation& anim, const EncodeOptions& opt, std::string* curve_fallback) {
  Model m;
  m.meta = {anim.vertex_count, uint32_t(anim.frames.size()), anim.frame_rate, opt.tolerance,
            bbox_diagonal(anim.frames[0]), ""};
  // The residual layer predicts from mesh neighbours when the file stores faces, and from
  // curve neighbours otherwise: it must see exactly what the decoder will.
  if (opt.connectivity) m.faces = opt.exact_face_order ? anim.faces : smaller_face_order(anim.faces);
  EncodeOptions plain_opt = opt;
  plain_opt.model = ModelChoice::None;
  m.curves = file_curves(anim, plain_opt, curve_fallback);
  return m;
}

// The fast profile without a PDE model: grid, low-rank model and fast payload all chosen by
// the fast coder's bytes (encoder/rate/fast_grid.h), no format 3 encode at all; one stage of
// progress.
bool encode_fast_alone(const Animation& anim, const EncodeOptions& opt, WorkMeter* meter, Model* m,
                       std::string* curve_fallback, std::string* error) {
  const Model base = file_base(anim, opt, curve_fallback);
  const double max_distance = opt.tolerance * base.meta.diag;
  FastLayerOptions fo;
  fo.snap_distance = snap_distance(anim, max_distance);
  fo.chunk_frames = opt.chunk_frames;
  fo.threads = opt.threads;
  fo.components = opt.low_rank;
  fo.meter = meter;
  const double refinement = opt.grid_refinement > 0     ? opt.grid_refinement
                            : opt.effort == kMinEffort ? kUntriedRefinement
                                                       : 0;
  const GridSearch search = opt.effort == kMaxEffort ? GridSearch::Walk : GridSearch::Bracket;
  meter->forecast({forecast_fast_grid_frames(anim, refinement > 0, search)});
  return choose_fast_grid(anim, base, max_distance, refinement, search, fo, m, error);
}

// The model every encode starts from: faces, curves, and the grid chosen by trial encodes
// of encode_plain. When the trials coded the whole animation, the winning trial is the
// plain encode itself: *plain receives it and *have_plain is set. When they coded part of
// it, below --effort 3, *follow receives what the winning trial chose.
bool start_model(const Animation& anim, const EncodeOptions& opt, GridStart* out, PlainEncode* plain, bool* have_plain,
                 std::optional<TrialChoices>* follow, std::string* curve_fallback, std::string* error) {
  Model& m = out->model;
  m = file_base(anim, opt, curve_fallback);
  const double L = m.meta.diag;
  EncodeOptions plain_opt = opt;
  plain_opt.model = ModelChoice::None;
  {
    ResidualOptions ro;
    ro.weights_source = out->weights;
    Traversal trav;
    traversal_for(m, ro, &trav);
    out->traversal = std::make_shared<const Traversal>(std::move(trav));
  }
  out->snap = snap_distance(anim, opt.tolerance * L);
  // Without a length asked for, the search (grid, low-rank model) codes the clip as one
  // chunk and the length is chosen for its result at the end: short chunks hide the
  // repeated poses far apart that the search's choices rest on.
  const uint32_t chunk_frames = opt.chunk_frames > 0 ? opt.chunk_frames : m.meta.frame_count;
  // The grid is chosen by whole plain encodes, which see the faces, curves and low-rank
  // model the file keeps: cheaper proxies (the residual layer alone, fewer coding orders)
  // ranked the grids wrongly on half of the corpus.
  if (opt.grid_refinement > 0 || opt.effort == kMinEffort) {
    m.residual = make_grid(anim, opt.tolerance * L, opt.grid_refinement > 0 ? opt.grid_refinement : kUntriedRefinement);
    m.residual.chunk_frames = chunk_frames;
    return quantize_to_grid(anim, m.residual, &out->rounded, error);
  }
  std::vector<PlainEncode> trials(kGridTrialSlots);
  const GridChoice choice =
      choose_grid(anim, opt.tolerance * L, opt.threads,
                  [&](const ResidualLayer& grid, const Animation& part, size_t slot, int threads) -> size_t {
                    GridStart s;
                    s.model = m;
                    s.model.meta.frame_count = uint32_t(part.frames.size());
                    s.model.residual = grid;
                    s.model.residual.chunk_frames = chunk_frames;
                    s.snap = out->snap;
                    s.weights = out->weights;
                    s.traversal = out->traversal;
                    s.meter = out->meter;
                    if (!quantize_to_grid(part, grid, &s.rounded, nullptr)) return SIZE_MAX;
                    EncodeOptions o = plain_opt;
                    o.threads = threads;
                    uint64_t bytes = 0;
                    if (!encode_plain(part, o, s, &trials[slot], nullptr, &bytes))
                      return SIZE_MAX;
                    return size_t(bytes);
                  },
                  opt.effort == kMaxEffort ? GridSearch::Walk : GridSearch::Bracket);
  m.residual = choice.grid;
  m.residual.chunk_frames = chunk_frames;
  *have_plain = choice.whole;
  const PlainEncode& won = trials[choice.slot];
  if (choice.whole) {
    *plain = std::move(trials[choice.slot]);
  } else if (opt.effort != kMaxEffort && !won.residual_only_coded.plan.chunks.empty()) {
    // The search over part of the clip chose for the whole: planning every order, layout and
    // low-rank candidate again for the whole clip took most of a long clip's encode.
    *follow = TrialChoices{won.residual_only_coded.plan.chunks[0], won.low_rank};
  }
  return quantize_to_grid(anim, m.residual, &out->rounded, error);
}

// The encode with the PDE motion model: fitted on every curve and segment with each allowed
// basis set and segment length, the estimated best of them per motion (one segmentation
// for the file), then only the motions that pay (encoder/rate/motion_*.h), into *m and *coded;
// plain.residual_only, the residual layer alone, is what they must beat.
bool encode_with_motions(const Animation& anim, const EncodeOptions& opt, const GridStart& start,
                         const PlainEncode& plain, Model* m, CodedResidual* coded, MotionChoiceReport* report,
                         std::string* curve_fallback, std::string* error) {
  const Model& alone = plain.residual_only;
  *m = start.model;
  // Without faces the plain encode has extracted the same curves already.
  m->curves = opt.connectivity ? file_curves(anim, opt, curve_fallback) : alone.curves;
  std::vector<Basis> bases = {Basis::Pde8};
  if (opt.model == ModelChoice::Pde32) bases = {Basis::Pde32};
  if (opt.model == ModelChoice::Pde) bases.push_back(Basis::Pde32);
  std::vector<uint32_t> lengths(std::begin(kAutoSegmentFrames), std::end(kAutoSegmentFrames));
  if (opt.segment_frames > 0) lengths = {opt.segment_frames};
  std::vector<std::vector<Segment>> fitted;
  for (uint32_t length : lengths)
    for (Basis basis : bases) {
      MotionModelOptions mo;
      mo.basis = basis;
      mo.segment_frames = length;
      mo.threads = opt.threads;
      // A tenth of the tolerance: the residual layer absorbs it at the frames, and
      // in-betweens stay within a tenth of the tolerance of the unrounded fit.
      mo.coefficient_error = 0.1 * opt.tolerance * m->meta.diag;
      fitted.emplace_back();
      if (!fit_motion_model(anim, m->curves, anim.frames[0], mo, &fitted.back(), error)) return false;
    }
  MotionAlternativesReport estimate;
  if (!choose_motion_alternative(*m, alone, plain.residual_only_coded, fitted, start.rounded, &m->segments, &estimate,
                                 error))
    return false;
  if (!opt.keep_all_motions && estimate.promising == 0) {
    // No motion comes near paying: the residual plan that would confirm it is skipped.
    *report = MotionChoiceReport();
    report->fitted = estimate.motions;
    return true;
  }
  MotionChoiceOptions mco;
  mco.keep_all = opt.keep_all_motions;
  return choose_motions(m, alone, plain.residual_only_coded, context_of(anim, opt, start), mco, report, error, coded);
}

std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// Which order the written FACE section holds, and what the coder's order would take.
void report_face_order(const std::vector<uint32_t>& faces, EncodeReport* rep) {
  const FaceOrderUse use = face_order_use(faces);
  rep->faces_in_coder_order = use.coder_order;
  rep->coder_order_connectivity_bytes = use.coder_order_bytes;
}

// The stages of an encode, in the order encode_animation runs them, for its WorkMeter.
enum Stage { kGridStage, kPlainStage, kChunkStage, kMotionStage, kFinishStage, kStageCount };

// Frame plans of one residual plan of F frames: one per coding order planned (both ends of
// the list and usually one more), then one per cluster layout on the order that won.
uint64_t residual_plan_frames(uint64_t F) {
  const ResidualPlanOptions po;
  return (std::min<size_t>(po.gop_sizes.size(), 3) + po.cluster_layouts.size()) * F;
}

// Forecast frame plans of each Stage of encoding `anim` with `opt`. follows_model: whether a
// grid trial of part of the clip kept a low-rank model for the whole clip to follow
// (start_model); assumed before the trials have run.
std::vector<uint64_t> forecast_stages(const Animation& anim, const EncodeOptions& opt, bool follows_model = true) {
  const uint64_t F = anim.frames.size();
  const bool fast = opt.profile == Profile::Fast;
  const bool low_rank = opt.low_rank != 0 && !fast;
  auto plain = [&](uint64_t frames) { return residual_plan_frames(frames) + (low_rank ? forecast_low_rank_frames(uint32_t(frames)) : 0); };
  std::vector<uint64_t> stages(kStageCount, 0);
  const bool trials = opt.grid_refinement == 0 && opt.effort != kMinEffort;
  const uint64_t trial_frames = grid_trial_frames(uint32_t(F), anim.vertex_count);
  if (trials) stages[kGridStage] = (opt.effort == kMaxEffort ? kWalkTrials : 2) * plain(trial_frames);
  // After trials of part of the clip, the whole clip's plan follows the winner (start_model):
  // one order and at most one layout, then one low-rank trial (two orders, then the layouts
  // on the better), or the whole low-rank search when the trial kept no model.
  const uint64_t followed = 2 * F + (!low_rank ? 0 : follows_model ? 4 * F : forecast_low_rank_frames(uint32_t(F)));
  if (!trials) stages[kPlainStage] = plain(F);
  else if (trial_frames < F) stages[kPlainStage] = opt.effort == kMaxEffort ? plain(F) : followed;
  // The chunk choice plans each length at --effort 3; otherwise it cuts the kept plan and
  // plans only a length that wins, which a clip too long to be one chunk always has.
  const bool chunk_choice = opt.chunk_frames == 0;
  if (chunk_choice && opt.effort == kMaxEffort) {
    for (uint32_t K : kChunkCandidates)
      if (K < F) stages[kChunkStage] += residual_plan_frames(F);
  } else if (chunk_choice && F > kMaxWholeClipFrames) {
    stages[kChunkStage] = residual_plan_frames(F);
  }
  if (opt.model != ModelChoice::None) stages[kMotionStage] = residual_plan_frames(F);
  // The fast layer (its own chunk lengths and low-rank models, about a plan's time) or block
  // flags, the in-between rule, the file written and decoded: not counted in frames, so
  // forecast as the time they take.
  stages[kFinishStage] = fast ? residual_plan_frames(F) : F;
  return stages;
}

// Every encode but the fast profile's without a PDE model: the grid and plain file by
// format 3 trial encodes, its chunk length, the PDE motions where asked for and they pay,
// then block flags (or, for the fast profile, its own layer over the chosen model) into *model.
bool encode_searched(const Animation& anim, const EncodeOptions& opt, WorkMeter* meter, Model* model,
                     EncodeReport* rep, std::string* error) {
  SpatialWeightsStore weights;
  GridStart start;
  start.weights = &weights;
  meter->forecast(forecast_stages(anim, opt));
  start.meter = meter;
  PlainEncode plain;
  Model& m = plain.model;
  CodedResidual& coded = plain.coded;  // what m's payloads code
  bool have_plain = false;
  std::optional<TrialChoices> follow;
  if (!start_model(anim, opt, &start, &plain, &have_plain, &follow, &rep->curve_fallback, error)) return false;
  meter->end_stage();  // the grid (kGridStage)
  if (follow) {
    const std::vector<uint64_t> stages = forecast_stages(anim, opt, follow->low_rank.components > 0);
    meter->forecast({stages.begin() + kPlainStage, stages.end()});
  }
  // The file without a PDE model comes first: with --model none it is the file, otherwise
  // the motion model has to beat it, value by value and as a whole file.
  if (!have_plain && !encode_plain(anim, opt, start, &plain, error, nullptr, follow ? &*follow : nullptr)) return false;
  meter->end_stage();
  WriteOptions wo;
  wo.connectivity = opt.connectivity;
  // The file the PDE model's motions must beat (the fast profile then replaces its layer).
  std::vector<uint8_t> file;
  if (opt.chunk_frames == 0) {
    const ChunkTrial trial = opt.effort == kMaxEffort ? ChunkTrial::Replan : ChunkTrial::Cut;
    if (!choose_chunk_frames(&m, &coded, context_of(anim, opt, start), trial, &file, error)) return false;
  } else {
    file = write_container(m, wo);
  }
  meter->end_stage();
  if (opt.model != ModelChoice::None) {
    Model pde;
    CodedResidual pde_coded;
    MotionChoiceReport mrep;
    std::string curve_fallback = rep->curve_fallback;
    if (!encode_with_motions(anim, opt, start, plain, &pde, &pde_coded, &mrep, &curve_fallback, error)) return false;
    rep->motions_fitted = mrep.fitted;
    if (mrep.kept > 0) {
      std::vector<uint8_t> with = write_container(pde, wo);
      if (opt.keep_all_motions || with.size() < file.size()) {
        file.swap(with);
        m = std::move(pde);
        coded = std::move(pde_coded);
        rep->motions_kept = mrep.kept;
        rep->curve_fallback = curve_fallback;
      }
    }
  }
  meter->end_stage();
  // The search measured without block flags; the chosen layer gets them where smaller.
  if (opt.profile == Profile::Fast) {
    FastLayerOptions fo;
    fo.snap_distance = start.snap;
    fo.chunk_frames = opt.chunk_frames;
    fo.threads = opt.threads;
    const bool choose_model = opt.low_rank == -1 && !has_motion_model(m);
    const std::vector<int32_t>* prediction = coded.prediction.empty() ? nullptr : &coded.prediction;
    if (choose_model ? !choose_fast_low_rank(&m, anim.frames, start.rounded, fo, error)
                     : !encode_fast_layer(&m, anim.frames, fo, error, prediction) ||
                           !fast_low_rank_basis(&m, error, coded.basis.values.empty() ? nullptr : &coded.basis.values))
      return false;
  } else if (!use_block_flags(&m, BlockFlagUse::WhenSmaller, error, &coded)) {
    return false;
  }
  *model = std::move(m);
  return true;
}

}  // namespace

// The float32 rounding may take at most a quarter of the tolerance.
double minimum_tolerance(const Animation& anim) {
  if (anim.frames.empty()) return 0;
  return 4.0 * float_output_error(anim) / bbox_diagonal(anim.frames[0]);
}

bool encode_animation(const Animation& anim, const EncodeOptions& opt, std::vector<uint8_t>* out,
                      EncodeReport* report, std::string* error) {
  auto start_time = std::chrono::steady_clock::now();
  if (!validate_animation(anim, error) || !check_render_limits(anim, error)) return false;
  if (!(opt.tolerance > 0 && opt.tolerance <= 0.5)) return fail(error, "tolerance must be in (0, 0.5]");
  if (opt.curve_points < 2) return fail(error, "target curve length must be at least 2 points");
  if (opt.low_rank < -1 || opt.low_rank > 64) return fail(error, "low-rank setting must be -1 (auto), 0 (off) or 1..64");
  if (!(opt.grid_refinement == 0 || (opt.grid_refinement >= 1 && opt.grid_refinement <= 16)))
    return fail(error, "grid refinement must be 0 (chosen by trial encodes) or in [1, 16]");
  if (opt.chunk_frames > kMaxChunkFrames)
    return fail(error, "chunk length must be 0 (chosen by the encoder) or in [1, " + std::to_string(kMaxChunkFrames) + "]");
  if (opt.effort < kMinEffort || opt.effort > kMaxEffort)
    return fail(error, "effort must be in [" + std::to_string(kMinEffort) + ", " + std::to_string(kMaxEffort) + "]");
  if (opt.model != ModelChoice::None && opt.low_rank > 0 && opt.keep_all_motions)
    return fail(error, "a low-rank model cannot be combined with a PDE motion model");
  if (!(bbox_diagonal(anim.frames[0]) > 0)) return fail(error, "rest pose has a zero bounding box (all vertices coincide)");
  if (opt.tolerance < minimum_tolerance(anim))
    return fail(error, "tolerance " + format_number(opt.tolerance) + " is below what float32 coordinates hold for this "
                       "input, " + format_number(minimum_tolerance(anim)) + " (rounding grows with the distance from the origin)");

  EncodeReport rep;
  WorkMeter meter(opt.progress);
  Model m;
  if (opt.profile == Profile::Fast && opt.model == ModelChoice::None) {
    if (!encode_fast_alone(anim, opt, &meter, &m, &rep.curve_fallback, error)) return false;
  } else if (!encode_searched(anim, opt, &meter, &m, &rep, error)) {
    return false;
  }
  WriteOptions wo;
  wo.connectivity = opt.connectivity;
  if (!choose_inbetween(&m, anim.frames, opt.inbetween, error)) return false;
  // The fast profile's faces in the Traversal layout (or Exact where the list is not in its
  // order): the Compact layout's walk took most of a format 4 file's opening.
  if (opt.profile == Profile::Fast) wo.face_layout = WriteOptions::FaceLayout::Traversal;
  // What a game draws besides positions: written once, never part of a trial.
  m.render = build_render_mesh(anim, m.faces, opt.attributes);
  m.placement = anim.placement;
  m.materials = m.render.empty() ? MaterialSet{} : anim.materials;
  std::vector<SectionInfo> sections;
  *out = write_container(m, wo, &sections);
  m.materials = MaterialSet{};  // written: an image's bytes are held once fewer for the check

  if (!measure_decoded(*out, anim, &rep.error, error)) return false;
  if (rep.error.max_error > opt.tolerance)
    return fail(error, "internal error: decoded max error " + std::to_string(rep.error.max_error) +
                           " exceeds the tolerance");
  rep.bytes = out->size();
  rep.connectivity_bytes = connectivity_bytes(sections);
  if (rep.connectivity_bytes > 0) report_face_order(m.faces, &rep);
  rep.low_rank_components = m.low_rank.components;
  rep.chunk_frames = std::min(m.residual.chunk_frames, m.meta.frame_count);
  rep.inbetween = m.meta.inbetween;
  rep.grid_refinement = grid_refinement(m.residual.step, opt.tolerance * m.meta.diag);
  for (const SectionInfo& s : sections) {
    if (s.tag == "LRNK") rep.low_rank_bytes = s.stored_bytes + s.header_bytes;
    if (s.tag == "SEGS" && !m.segments.empty()) rep.model_bytes = s.raw_bytes;
  }
  rep.motion_bytes = rep.bytes - rep.connectivity_bytes;
  rep.vertices = anim.vertex_count;
  rep.frames = uint32_t(anim.frames.size());
  rep.segments = uint32_t(m.segments.size());
  rep.bpvf = 8.0 * double(rep.bytes) / (double(rep.vertices) * rep.frames);
  rep.curves = curve_report(m.curves, anim.frames[0]);
  rep.encode_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  meter.end_stage();
  if (report) *report = rep;
  return true;
}

}  // namespace dcurve
