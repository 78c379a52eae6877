#include "encoder/rate/low_rank_choice.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "codec/common/error.h"
#include "codec/common/low_rank.h"
#include "codec/common/residual.h"
#include "codec/compress/low_rank_writer.h"
#include "codec/compress/residual_encoder.h"
#include "codec/compress/residual_values.h"
#include "codec/decompress/model_prediction.h"
#include "encoder/rate/frame_poses.h"
#include "encoder/rate/low_rank.h"
#include "encoder/rate/plan_steps.h"
#include "encoder/rate/residual_plan.h"

namespace dcurve {
namespace {

// Component counts screened (those the PCA provides), and the basis step (grid units) they
// are screened at; the best count is then screened at the other steps. The residual layer
// corrects what the basis rounds off, so the best step trades basis bytes against
// residual bytes. On fine grids that step is coarser than a grid step, hence steps up to
// 4: a coarse basis costs few bytes, and the residual layer absorbs its rounding.
constexpr uint32_t kComponentCounts[] = {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64};
constexpr double kFirstStep = 0.15;
constexpr double kOtherSteps[] = {0.1, 0.25, 0.4, 0.6, 1.0, 1.6, 2.5, 4.0};
// Frames the screening estimate samples (every ceil(F / this)-th frame).
constexpr uint32_t kScreenFrames = 24;
// Screened candidates and full trials of a typical low-rank choice, for the progress
// forecast only (the inputs of encode-bench.sh ranged over about 20-90 and 1-6).
constexpr uint64_t kForecastCandidates = 40, kForecastTrials = 3;
// Counts past the best one screened before giving up on larger ones: every count, since the
// estimate is not unimodal in K (the net saving can fall over the small counts and rise
// again to its best at a large one).
constexpr int kPatience = int(std::size(kComponentCounts));
// Counts screened at every basis step (the best ones at the first step).
constexpr int kRefinedCounts = 2;
// The screening estimate ignores the coder's contexts and the per-cluster predictor choice,
// so it misjudges savings both ways. On inputs of more than kCheapTrial vertex-frames a
// full trial runs only when the estimated saving exceeds the section's raw bytes
// (kTrialSavingFactor), which bounds the encode time lost to losing trials; smaller
// inputs, whose trials are cheap, try one from kCheapTrialSavingFactor times, since a
// candidate estimated just below its section can still win. The large inputs' bar is no
// higher than 1.0 because the per-cluster choice draws more from a model than the
// estimate's Model-only plan shows, so winning trials can be estimated only a little above
// their section; a lower bar added only losing trials.
constexpr double kTrialSavingFactor = 1.0, kCheapTrialSavingFactor = 0.75;
constexpr double kCheapTrial = double(1 << 18);
// The low-rank rescue (choose_low_rank) screens the counts the first basis step cut off
// while each saves at least this share of its section, and refines the best one only when
// it does. At the finest step where a cut count fits, its section is near the residual
// payload: saving less than half of it, the model explains too little of the residual for
// any step to make it worth a trial, and screening such counts at every step would cost
// much of an encode's time on inputs where no model is kept.
constexpr double kRescueRatio = 0.5;
// Posed anchors are screened only when some frame turns at least this far (radians) against
// frame 0: below it the poses are nearly the identity, and the translation they would remove
// costs the unposed model three components at most.
constexpr double kMinPoseAngle = 0.05;
// Above this many multiply-adds the F x F Gram matrix is not worth building automatically.
constexpr double kMaxGramWork = 4e9;

// The frame average enters every frame's prediction the same way: it is stored about as
// finely as the basis (2^-mean_shift ~ step, at most 8 bits below the grid). A frame anchor's
// values are grid integers, exact at shift 0.
uint32_t mean_shift_for(const GridComponents& pca, double step) {
  if (pca.anchor != kMeanAnchor) return 0;
  return uint32_t(std::clamp(std::lround(-std::log2(step)), 0L, 8L));
}

// Estimated bits of each frame's residuals under `plan` (indexed by frame), one context per
// frame: only compared with the same estimate of another plan.
std::vector<double> frame_bits(const Model& m, const std::vector<int32_t>& q, const ResidualPlan& plan,
                               const ResidualOptions& ro) {
  const size_t n = size_t(m.meta.vertex_count) * 3;
  const std::vector<int64_t> r = residual_values(m, q, plan, ro);
  const std::vector<CodedFrame> coded = coded_frames(plan);
  std::vector<double> bits(m.meta.frame_count, 0.0);
  const std::vector<uint8_t> contexts(n, 0);
  for (size_t k = 0; k < coded.size() && (k + 1) * n <= r.size(); ++k) {
    const std::vector<int64_t> slice(r.begin() + std::ptrdiff_t(k * n), r.begin() + std::ptrdiff_t((k + 1) * n));
    bits[coded[k].frame] = estimate_residual_bits(slice, contexts);
  }
  return bits;
}

// The counts halfway from K to its neighbours in `sorted` (ascending, holding K) that it
// does not hold.
std::vector<uint32_t> halfway_counts(const std::vector<uint32_t>& sorted, uint32_t K) {
  std::vector<uint32_t> out;
  const auto at = std::find(sorted.begin(), sorted.end(), K);
  if (at == sorted.end()) return out;
  if (at != sorted.begin()) out.push_back((*(at - 1) + K) / 2);
  if (at + 1 != sorted.end()) out.push_back((K + *(at + 1)) / 2);
  out.erase(std::remove_if(out.begin(), out.end(),
                           [&](uint32_t mid) { return std::binary_search(sorted.begin(), sorted.end(), mid); }),
            out.end());
  return out;
}

struct Candidate {
  LowRankModel model;
  const GridComponents* pca = nullptr;
  double basis_step = 0;
  double saved_bytes = 0;    // estimated residual bytes saved
  double section_bytes = 0;  // the LRNK section's raw bytes
  double net_bytes = 0;      // the difference
};

// Every `stride`-th frame of an encode: the screening estimate's sample. With the Model
// predictor alone, frames are coded independently, so a sample estimates the whole.
struct FrameSample {
  std::vector<uint32_t> frames;  // indices into the full animation
  Model model;                   // counts, faces, curves and grid for frames.size() frames
  std::vector<std::vector<float>> input;
  std::vector<int32_t> rounded;
};

// Every how many frames the screening samples one.
uint32_t screen_stride(uint32_t F) { return ((F + kScreenFrames - 1) / kScreenFrames) | 1; }

FrameSample sample_frames(const Model& model, const std::vector<std::vector<float>>& frames,
                          const std::vector<int32_t>& rounded, uint32_t stride) {
  const size_t n = size_t(model.meta.vertex_count) * 3;
  FrameSample s;
  s.model.meta = model.meta;
  s.model.faces = model.faces;
  s.model.curves = model.curves;
  s.model.residual.step = model.residual.step;
  std::copy(model.residual.origin, model.residual.origin + 3, s.model.residual.origin);
  for (uint32_t f = 0; f < model.meta.frame_count; f += stride) {
    s.frames.push_back(f);
    s.input.push_back(frames[f]);
    s.rounded.insert(s.rounded.end(), rounded.begin() + std::ptrdiff_t(f * n),
                     rounded.begin() + std::ptrdiff_t((f + 1) * n));
  }
  s.model.meta.frame_count = uint32_t(s.frames.size());
  return s;
}

// Whether any chunk of `plan` was planned with a Fit weight table per frame.
bool any_geometry_per_frame(const ResidualPlan& plan) {
  return std::any_of(plan.chunks.begin(), plan.chunks.end(),
                     [](const PredictorPlan& chunk) { return geometry_per_frame(chunk); });
}

// Residual plan and payload of `trial` with its low-rank prediction, coded->prediction (full
// trial): every coding order of plan_options planned one predictor per frame, then the
// per-cluster stage on the order that codes smallest, as the plan without a model is made.
// Its plan and values go to *coded.
bool encode_with_prediction(Model* trial, CodedResidual* coded, const std::vector<std::vector<float>>& frames,
                            const std::vector<int32_t>& rounded, double snap_distance,
                            const ResidualPlanOptions& plan_options, const ResidualOptions& shared,
                            std::string* error) {
  ResidualOptions ro = shared;
  ro.model_prediction = &coded->prediction;
  coded->resi.values = rounded;
  coded->resi.plan = choose_chunked_plan(*trial, frames, snap_distance, &coded->resi.values, ro, plan_options);
  trial->residual.payload = encode_residuals(*trial, coded->resi.values, coded->resi.plan, ro);
  if (trial->residual.payload.empty()) return fail(error, "internal error: the low-rank residual plan is invalid");
  return true;
}

// One low-rank choice: the anchors (frame average, first frame, each posed), the screening
// of counts and steps on a sample of frames, then full trials of the promising candidates.
// Each step is a member; they share the inputs and what earlier steps found.
class LowRankSearch {
 public:
  LowRankSearch(Model* model, const PlannedResidual& planned, const EncodeContext& context,
                const LowRankChoiceOptions& options, std::string* error)
      : model_(model), planned_(planned), frames_(context.frames), rounded_(context.rounded),
        snap_(context.snap_distance), write_options_(context.write), threads_(context.plan.threads),
        meter_(context.plan.meter), geometry_per_frame_(context.plan.geometry_per_frame),
        try_geometry_per_frame_(context.plan.try_geometry_per_frame),
        shared_(context.shared), options_(options), error_(error),
        F_(model->meta.frame_count), n_(size_t(model->meta.vertex_count) * 3), forced_(options.components > 0) {}

  // False only on an internal error; *report as choose_low_rank fills it.
  bool run(LowRankChoiceReport* report, CodedResidual* kept);

 private:
  void add_anchor(uint32_t anchor, bool posed);
  void build_anchors();
  void build_sample();
  bool search();
  bool follow(const LowRankPick& pick);
  bool quantize(const GridComponents& pca, uint32_t K, double step, Model* trial, CodedPayload* basis);
  bool screen(const GridComponents& pca, uint32_t K, double step, bool* screened, std::vector<Candidate>* into);
  bool screen(const GridComponents& pca, uint32_t K, double step, bool* screened) {
    return screen(pca, K, step, screened, &candidates_);
  }
  const Candidate* best_of(const GridComponents* pca, bool by_ratio, const std::vector<uint32_t>& skip = {}) const;
  const Candidate* best_rescued(const GridComponents* pca) const;
  bool screen_anchor(const GridComponents& pca);
  bool screen_first_step(const GridComponents& pca, const std::vector<uint32_t>& counts, size_t* cut);
  bool refine_steps(const GridComponents& pca);
  bool screen_larger_counts(const GridComponents& pca, const Candidate** best);
  bool screen_halfway_counts(const GridComponents& pca, const Candidate& best);
  bool rescue_cut_counts(const GridComponents& pca, const std::vector<uint32_t>& counts, size_t cut);
  bool posed_beats_twin(size_t i, bool* beats);
  bool run_trials();
  bool run_trial(const Candidate& c, bool from_rescue, uint64_t* bytes);
  bool worth_a_trial(const Candidate& c) const;

  Model* model_;
  const PlannedResidual& planned_;
  const std::vector<std::vector<float>>& frames_;
  const std::vector<int32_t>& rounded_;
  const double snap_;
  const WriteOptions& write_options_;
  const int threads_;  // 0: all cores; the result never depends on it
  WorkMeter* const meter_;  // may be null
  // The geometry-frame rule the full trials plan with: the encode's, or a followed pick's.
  bool geometry_per_frame_, try_geometry_per_frame_;
  ResidualOptions shared_;  // one traversal and the encode's weight tables for every walk
  const LowRankChoiceOptions& options_;
  std::string* error_;
  const uint32_t F_;
  const size_t n_;
  const bool forced_;

  LowRankChoiceReport rep_;
  Traversal owned_traversal_;
  std::vector<double> bits_without_;  // what the residual layer pays today, frame by frame
  std::vector<GridComponents> pcas_;  // built before any candidate points into it
  size_t posed_from_ = 0;             // the posed anchors follow their unposed twins
  FramePoses poses_;
  FrameSample sample_;
  double sample_scale_ = 1;
  std::vector<std::vector<AxisRun>> sample_runs_;
  ResidualPlanOptions screen_options_;
  std::vector<Candidate> candidates_, rescued_;
  std::vector<BasisMemo> memos_;  // per anchor
  uint64_t best_bytes_ = 0;
  Model best_model_;
  CodedResidual best_coded_;  // what best_model_'s payload codes
};

// One anchor's components: of the rounded frames, or (posed) of the frames carried into frame
// 0's pose, which poses_ must hold.
void LowRankSearch::add_anchor(uint32_t anchor, bool posed) {
  const uint32_t max_components = std::min<uint32_t>(kMaxLowRankComponents, F_ - 1);
  pcas_.push_back(grid_components(posed ? poses_.aligned : rounded_, F_, n_, max_components, anchor));
  if (!posed) return;
  pcas_.back().poses = poses_.poses;
  std::copy(poses_.centre, poses_.centre + 3, pcas_.back().pose_centre);
}

// Two anchors, each screened over every count: the frame average, the classic centre, and
// the first frame, often the cleanest shape of an animation (a rest pose, modelled or
// generated, whose regular mesh codes in far fewer bytes than the average's blur of poses),
// at the price of components that must also span the average's offset from it. Neither
// anchor wins on every input, hence the screening of both. The first frame is screened only
// when it codes smaller than the rounded average: its shape is its one advantage, and where
// the modelled mesh is no cleaner than the average, screening it would multiply the encode
// time for nothing. Each anchor again in frame 0's pose, for bodies that turn.
void LowRankSearch::build_anchors() {
  add_anchor(kMeanAnchor, false);
  if (options_.first_frame_anchor && !pcas_[0].mean.empty()) {
    std::vector<int32_t> average(n_);
    for (size_t i = 0; i < n_; ++i) average[i] = int32_t(std::lround(pcas_[0].mean[i]));
    const std::vector<int32_t> first(rounded_.begin(), rounded_.begin() + std::ptrdiff_t(n_));
    if (anchor_bytes(*model_, first, threads_, shared_.traversal) <
        anchor_bytes(*model_, average, threads_, shared_.traversal))
      add_anchor(0, false);
  }
  posed_from_ = pcas_.size();
  if (options_.posed_anchors && !forced_ && estimate_frame_poses(rounded_, F_, n_, &poses_) &&
      poses_.max_angle >= kMinPoseAngle) {
    for (size_t i = 0; i < posed_from_; ++i) add_anchor(pcas_[i].anchor, true);
  }
  memos_.resize(pcas_.size());
}

// Screening: the Model predictor alone, time order, one predictor per frame, on a sample of
// the frames, against today's bits of the same frames.
void LowRankSearch::build_sample() {
  screen_options_.kinds = 1u << int(PredictorKind::Model);
  // Without Fit: offered here too, it moved the screening's ranking towards candidates
  // whose full encodes were larger.
  screen_options_.spatial_modes = ~(1u << int(SpatialMode::Fit));
  screen_options_.gop_sizes = {1};
  // Without the per-cluster stage: with one predictor kind it has little to choose, and its
  // two layouts planned every sampled frame twice more. The full trials keep it.
  screen_options_.cluster_layouts.clear();
  screen_options_.threads = threads_;
  screen_options_.meter = meter_;
  // An odd stride: hierarchical coding orders make every power-of-two-th frame dearer.
  sample_ = sample_frames(*model_, frames_, rounded_, screen_stride(F_));
  sample_scale_ = double(F_) / double(sample_.frames.size());
  // Every screening plan snaps the same frames on the same grid.
  sample_runs_ = plan_axis_runs(sample_.model, sample_.input, snap_, threads_);
  screen_options_.axis_runs = &sample_runs_;
}

// K components of `pca` at `step` into trial->low_rank, refitted to the frames they came
// from; *basis receives what its basis payload codes. False when a value
// leaves the format's ranges.
bool LowRankSearch::quantize(const GridComponents& pca, uint32_t K, double step, Model* trial,
                             CodedPayload* basis) {
  const std::vector<int32_t>& refit = pca.poses.empty() ? rounded_ : poses_.aligned;
  return quantize_low_rank(pca, K, step, mean_shift_for(pca, step), threads_, trial, &refit,
                           &memos_[size_t(&pca - pcas_.data())], shared_.traversal, basis);
}

// Screens count K at `step` into `into`. A model whose section alone outweighs today's
// residual payload cannot pay and is skipped (*screened false).
bool LowRankSearch::screen(const GridComponents& pca, uint32_t K, double step, bool* screened,
                           std::vector<Candidate>* into) {
  *screened = false;
  Model trial = *model_;
  CodedPayload basis;
  if (!quantize(pca, K, step, &trial, &basis)) return true;
  const double section = double(low_rank_bytes(trial).size());
  if (!forced_ && section >= double(model_->residual.payload.size())) return true;
  // The sampled frames' predictions, from the values the basis payload codes.
  std::vector<int32_t> sampled(sample_.frames.size() * n_), q = sample_.rounded;
  for (size_t j = 0; j < sample_.frames.size(); ++j)
    low_rank_frame(trial.low_rank, sample_.frames[j], basis.values.data(), n_, sampled.data() + j * n_);
  ResidualOptions ro = shared_;
  ro.model_prediction = &sampled;
  const ResidualPlan plan = choose_chunked_plan(sample_.model, sample_.input, snap_, &q, ro, screen_options_);
  const std::vector<double> bits = frame_bits(sample_.model, q, plan, ro);
  double saved = 0;
  for (size_t j = 0; j < sample_.frames.size(); ++j)
    saved += std::max(0.0, bits_without_[sample_.frames[j]] - bits[j]) / 8 * sample_scale_;
  into->push_back({std::move(trial.low_rank), &pca, step, saved, section, saved - section});
  ++rep_.screened;
  *screened = true;
  return true;
}

// The best candidate of one anchor: by net bytes, or (by_ratio) by saved bytes per section
// byte; `skip`: counts left out.
const Candidate* LowRankSearch::best_of(const GridComponents* pca, bool by_ratio,
                                        const std::vector<uint32_t>& skip) const {
  const Candidate* best = nullptr;
  for (const Candidate& c : candidates_) {
    if (c.pca != pca || std::find(skip.begin(), skip.end(), c.model.components) != skip.end()) continue;
    if (!best || (by_ratio ? c.saved_bytes * best->section_bytes > best->saved_bytes * c.section_bytes
                           : c.net_bytes > best->net_bytes))
      best = &c;
  }
  return best;
}

const Candidate* LowRankSearch::best_rescued(const GridComponents* pca) const {
  const Candidate* best = nullptr;
  for (const Candidate& c : rescued_)
    if (c.pca == pca && (!best || c.net_bytes > best->net_bytes)) best = &c;
  return best;
}

// Counts the first step cut off (from counts[cut] on, ascending), each at the first coarser
// step where its section fits, set apart (`rescued_`) so that nothing else changes: the
// first step's cut can hide the best count of an anchor (a large count at a coarse step
// can beat every small count the first step kept), but ranking the rescued counts with the
// others moves the trials away from the winners of inputs the rescue does not help. They
// get a trial of their own. The best of them is refined as the screened counts are: at
// every other step, then halfway to its neighbours at its best step; while they save
// enough (kRescueRatio).
bool LowRankSearch::rescue_cut_counts(const GridComponents& pca, const std::vector<uint32_t>& counts, size_t cut) {
  if (!options_.rescue_cut_counts || forced_) return true;
  auto saves_enough = [](const Candidate& c) { return c.saved_bytes >= kRescueRatio * c.section_bytes; };
  // A count's section grows with K, so a larger count fits no finer step than the last.
  size_t from = 0;
  for (size_t i = cut; i < counts.size(); ++i) {
    bool screened = false;
    for (; from < std::size(kOtherSteps); ++from) {
      if (kOtherSteps[from] <= kFirstStep) continue;
      if (!screen(pca, counts[i], kOtherSteps[from], &screened, &rescued_)) return false;
      if (screened) break;
    }
    if (!screened || !saves_enough(rescued_.back())) break;
  }
  const Candidate* top = best_rescued(&pca);
  if (!top || !saves_enough(*top)) return true;
  const uint32_t top_K = top->model.components;
  const double top_step = top->basis_step;
  for (double other : kOtherSteps) {
    // Tried above, top_step itself, or finer than the first step, where top_K was cut.
    if (other <= top_step) continue;
    bool screened = false;
    if (!screen(pca, top_K, other, &screened, &rescued_)) return false;
  }
  const double best_step = best_rescued(&pca)->basis_step;
  for (uint32_t mid : halfway_counts(counts, top_K)) {
    bool screened = false;
    if (!screen(pca, mid, best_step, &screened, &rescued_)) return false;
  }
  return true;
}

// Every count at the first step, ascending, until kPatience counts in a row fail to beat the
// best or one's section outweighs the payload (*cut: its index, counts.size() if none).
bool LowRankSearch::screen_first_step(const GridComponents& pca, const std::vector<uint32_t>& counts, size_t* cut) {
  double best_net = -HUGE_VAL;
  int worse = 0;
  *cut = counts.size();
  for (size_t i = 0; i < counts.size(); ++i) {
    if (worse >= kPatience) break;
    bool screened = false;
    if (!screen(pca, counts[i], kFirstStep, &screened)) return false;
    if (!screened) {  // larger counts cost more still
      *cut = i;
      break;
    }
    if (candidates_.back().net_bytes > best_net) {
      best_net = candidates_.back().net_bytes;
      worse = 0;
    } else {
      ++worse;
    }
  }
  return true;
}

// Other steps for the best count and the runner-up, unless even the coarsest could not pay:
// a coarser basis saves less, and its section shrinks by about the step ratio at most. When
// no count pays at the first step, the one that comes closest relative to its section: a
// coarser step may make it pay. The runner-up too, since the first step often ranks the top
// counts closely and the best step differs by count: the runner-up at its own best step
// can code smaller than the first at its.
bool LowRankSearch::refine_steps(const GridComponents& pca) {
  std::vector<uint32_t> refined;
  for (int round = 0; round < kRefinedCounts; ++round) {
    const Candidate* first = best_of(&pca, false, refined);
    if (first && first->net_bytes <= 0) first = best_of(&pca, true, refined);
    if (!first) break;
    const uint32_t K = first->model.components;  // screen may move the candidates
    refined.push_back(K);
    if (first->saved_bytes <= kFirstStep / kOtherSteps[std::size(kOtherSteps) - 1] * first->section_bytes) continue;
    for (double step : kOtherSteps) {
      bool screened = false;
      if (!screen(pca, K, step, &screened)) return false;
    }
  }
  return true;
}

// When the best count is the largest screened, the first step cut off the next ones (their
// section alone outweighed the payload) before the net saving was seen to fall: at the
// refined, coarser step they may pay, and beat the best count, so they are screened at it,
// upwards while they are. *best follows.
bool LowRankSearch::screen_larger_counts(const GridComponents& pca, const Candidate** best) {
  const uint32_t K = (*best)->model.components;
  const bool cut_off = std::none_of(candidates_.begin(), candidates_.end(), [&](const Candidate& c) {
    return c.pca == &pca && c.model.components > K;
  });
  if (!cut_off) return true;
  const double step = (*best)->basis_step;
  for (uint32_t larger : kComponentCounts) {
    if (larger <= K || larger > pca.weights.size()) continue;
    bool screened = false;
    if (!screen(pca, larger, step, &screened)) return false;
    if (!screened) break;
  }
  *best = best_of(&pca, false);
  return true;
}

// Counts between the screened ones, halfway to the best one's screened neighbours, at the
// best one's step: near its best the net saving is smooth enough in K for that to find what
// the list misses. After the step search, so that a count found here competes at a refined
// step, not the first one. Once: a second halving follows the estimate's noise between
// close counts to one whose full encode is larger, and only the best estimate is encoded.
bool LowRankSearch::screen_halfway_counts(const GridComponents& pca, const Candidate& best) {
  std::vector<uint32_t> screened_counts;
  for (const Candidate& c : candidates_)
    if (c.pca == &pca) screened_counts.push_back(c.model.components);
  std::sort(screened_counts.begin(), screened_counts.end());
  screened_counts.erase(std::unique(screened_counts.begin(), screened_counts.end()), screened_counts.end());
  const double step = best.basis_step;
  const uint32_t K = best.model.components;  // screen may move the candidates
  for (uint32_t mid : halfway_counts(screened_counts, K)) {
    bool screened = false;
    if (mid <= pca.weights.size() && !screen(pca, mid, step, &screened)) return false;
  }
  return true;
}

bool LowRankSearch::screen_anchor(const GridComponents& pca) {
  const uint32_t available = uint32_t(pca.weights.size());
  std::vector<uint32_t> counts;
  if (forced_ && available > 0) counts.push_back(std::min(uint32_t(options_.components), available));
  for (uint32_t K : kComponentCounts)
    if (!forced_ && K <= available) counts.push_back(K);
  size_t cut = counts.size();
  if (!screen_first_step(pca, counts, &cut) || !refine_steps(pca)) return false;
  const Candidate* best = best_of(&pca, false);
  if (forced_ || !best || best->net_bytes <= 0) return rescue_cut_counts(pca, counts, cut);
  if (!screen_larger_counts(pca, &best) || !screen_halfway_counts(pca, *best)) return false;
  return rescue_cut_counts(pca, counts, cut);
}

// A posed anchor is screened in full only when it beats its unposed twin at the twin's best
// count and step, and otherwise leaves no candidate behind (no trial): the pose helps bodies
// that turn while they deform, and screening and trying every posed anchor slows the
// encodes of the others for the same file. The one screening at the twin's best tells them
// apart: where the posed anchor's estimate beats the twin's there, its trial can win;
// where it does not, its trials lose.
bool LowRankSearch::posed_beats_twin(size_t i, bool* beats) {
  *beats = false;
  const Candidate* twin = best_of(&pcas_[i - posed_from_], false);
  if (!twin) return true;
  const uint32_t K = twin->model.components;
  const double step = twin->basis_step, net = twin->net_bytes;
  bool screened = false;
  if (!screen(pcas_[i], K, step, &screened)) return false;
  if (!screened) return true;
  if (candidates_.back().net_bytes <= net) {
    candidates_.pop_back();
    return true;
  }
  *beats = true;
  return true;
}

bool LowRankSearch::worth_a_trial(const Candidate& c) const {
  const bool cheap = double(F_) * model_->meta.vertex_count <= kCheapTrial;
  return forced_ || c.saved_bytes > (cheap ? kCheapTrialSavingFactor : kTrialSavingFactor) * c.section_bytes;
}

// The full trial of c (one of `rescued_` when from_rescue): *bytes its whole file, kept when
// the smallest so far. With a good model the coding order matters little: time order and
// the order chosen without one are tried.
bool LowRankSearch::run_trial(const Candidate& c, bool from_rescue, uint64_t* bytes) {
  ResidualPlanOptions trial_plan;
  trial_plan.geometry_per_frame = geometry_per_frame_;
  trial_plan.try_geometry_per_frame = try_geometry_per_frame_;
  trial_plan.gop_sizes = {1};
  trial_plan.threads = threads_;
  trial_plan.meter = meter_;
  const std::vector<uint32_t>& order_without = planned_.plan.chunks[0].order;
  if (order_without.size() > 2 && order_without[1] > 1) trial_plan.gop_sizes.push_back(order_without[1]);
  // The candidate quantized again (as screened: the memo makes it quick) for the values its
  // basis payload codes, which give the Model prediction of every frame.
  Model trial = *model_;
  CodedResidual coded;
  if (!quantize(*c.pca, c.model.components, c.basis_step, &trial, &coded.basis) ||
      trial.low_rank.basis_payload != c.model.basis_payload || trial.low_rank.coeffs != c.model.coeffs)
    return fail(error_, "internal error: a screened low-rank model quantizes differently");
  coded.prediction = low_rank_prediction(trial.low_rank, coded.basis.values, F_, n_);
  if (!encode_with_prediction(&trial, &coded, frames_, rounded_, snap_, trial_plan, shared_, error_)) return false;
  ++rep_.trials;
  *bytes = write_container(trial, write_options_).size();
  if (*bytes < best_bytes_) {
    best_bytes_ = *bytes;
    best_model_ = std::move(trial);
    best_coded_ = std::move(coded);
    rep_.kept = {c.model.components, c.pca->anchor, !c.pca->poses.empty(), c.basis_step,
                 any_geometry_per_frame(best_coded_.resi.plan)};
    rep_.rescued = from_rescue;
  }
  return true;
}

// Full trials of the promising candidates, best estimate first; the smallest whole file wins.
// Trials per anchor: the estimate ranks candidates of one anchor well enough, but not the
// two anchors against each other (it can prefer the anchor whose best codes larger).
// Skipping the other anchor's trial when its estimate falls a few percent behind loses
// files: the estimate can put the winning anchor far behind, and a grid whose best anchor
// went untried also misleads the grid search, which compares whole files.
bool LowRankSearch::run_trials() {
  std::stable_sort(candidates_.begin(), candidates_.end(),
                   [](const Candidate& a, const Candidate& b) { return a.net_bytes > b.net_bytes; });
  best_bytes_ = forced_ ? UINT64_MAX : rep_.bytes_without;
  std::vector<std::pair<const GridComponents*, uint32_t>> tried;  // anchor, count
  // An anchor whose first trial saved less than half its estimate gets a second one, of
  // another count: the estimate misjudged that count, maybe not the next.
  std::vector<const GridComponents*> disappointed;
  for (const Candidate& c : candidates_) {
    const auto same_anchor = [&](const std::pair<const GridComponents*, uint32_t>& t) { return t.first == c.pca; };
    const uint32_t allowed = options_.max_trials + uint32_t(std::count(disappointed.begin(), disappointed.end(), c.pca));
    if (uint32_t(std::count_if(tried.begin(), tried.end(), same_anchor)) >= allowed) continue;
    if (!worth_a_trial(c)) continue;
    // A second trial of the same count at another step mostly repeats the first's error.
    if (std::find(tried.begin(), tried.end(), std::make_pair(c.pca, c.model.components)) != tried.end()) continue;
    tried.emplace_back(c.pca, c.model.components);
    uint64_t bytes = 0;
    if (!run_trial(c, false, &bytes)) return false;
    const bool first_of_anchor = std::count_if(tried.begin(), tried.end(), same_anchor) == 1;
    if (!forced_ && first_of_anchor && double(rep_.bytes_without) - double(bytes) < 0.5 * c.net_bytes)
      disappointed.push_back(c.pca);
  }
  // Per anchor, the best rescued count gets one more trial when its estimate beats every
  // candidate the anchor had: an anchor whose best count the first step cut off still gets
  // it tried, and since only a smaller whole file replaces the best, no file grows.
  for (const GridComponents& pca : pcas_) {
    const Candidate* c = best_rescued(&pca);
    const Candidate* screened = best_of(&pca, false);
    if (!c || (screened && c->net_bytes <= screened->net_bytes) || !worth_a_trial(*c)) continue;
    uint64_t bytes = 0;
    if (!run_trial(*c, true, &bytes)) return false;
  }
  return true;
}

// The screening of every anchor, then the full trials of the promising candidates.
bool LowRankSearch::search() {
  bits_without_ = frame_bits(*model_, planned_.values, planned_.plan, shared_);
  build_anchors();
  build_sample();
  for (size_t i = 0; i < pcas_.size(); ++i) {
    if (!pcas_[i].poses.empty()) {
      bool beats = false;
      if (!posed_beats_twin(i, &beats)) return false;
      if (!beats) continue;
    }
    if (!screen_anchor(pcas_[i])) return false;
  }
  return run_trials();
}

// The one full trial of `pick`, unless this clip cannot have it (its frames do not turn for
// a posed anchor, or give fewer components).
bool LowRankSearch::follow(const LowRankPick& pick) {
  if (pick.components == 0) return true;
  if (pick.posed && !estimate_frame_poses(rounded_, F_, n_, &poses_)) return true;
  add_anchor(pick.anchor, pick.posed);
  memos_.resize(1);
  if (pick.components > pcas_[0].weights.size()) return true;
  Model trial = *model_;
  CodedPayload basis;
  if (!quantize(pcas_[0], pick.components, pick.basis_step, &trial, &basis)) return true;
  Candidate c;
  c.model = std::move(trial.low_rank);
  c.pca = &pcas_[0];
  c.basis_step = pick.basis_step;
  // The trial's rule, as its other choices; a one-table pick may still try tables per frame
  // where the encode does.
  geometry_per_frame_ = pick.geometry_per_frame;
  try_geometry_per_frame_ = try_geometry_per_frame_ && !pick.geometry_per_frame;
  best_bytes_ = rep_.bytes_without;
  uint64_t bytes = 0;
  return run_trial(c, false, &bytes);
}

bool LowRankSearch::run(LowRankChoiceReport* report, CodedResidual* kept) {
  rep_.bytes_without = rep_.bytes = write_container(*model_, write_options_).size();
  if (report) *report = rep_;
  if (options_.components == 0) return true;
  if (options_.components > int(kMaxLowRankComponents))
    return fail(error_, "low-rank component count must be at most " + std::to_string(kMaxLowRankComponents));
  if (has_motion_model(*model_)) {
    if (forced_) return fail(error_, "a low-rank model cannot be combined with a PDE motion model");
    return true;
  }
  if (!forced_ && (F_ < 3 || double(F_) * F_ * double(n_) > kMaxGramWork)) return true;
  shared_.model_prediction = nullptr;
  shared_.traversal = &traversal_for(*model_, shared_, &owned_traversal_);
  if (!(options_.follow ? follow(*options_.follow) : search())) return false;
  if (rep_.kept.components > 0) {
    *model_ = std::move(best_model_);
    if (kept) *kept = std::move(best_coded_);
    rep_.bytes = best_bytes_;
  }
  if (report) *report = rep_;
  return true;
}

}  // namespace

bool choose_low_rank(Model* model, const PlannedResidual& planned, const EncodeContext& context,
                     const LowRankChoiceOptions& options, LowRankChoiceReport* report, std::string* error,
                     CodedResidual* kept) {
  LowRankSearch search(model, planned, context, options, error);
  return search.run(report, kept);
}

// Screening plans each sampled frame once per candidate (a few dozen on the corpus), and
// about three full trials plan the clip in two orders, then both layouts on the better.
uint64_t forecast_low_rank_frames(uint32_t F) {
  const uint64_t sampled = (F + screen_stride(F) - 1) / screen_stride(F);
  return kForecastCandidates * sampled + kForecastTrials * 4 * uint64_t(F);
}

}  // namespace dcurve
