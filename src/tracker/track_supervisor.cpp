#include "tracker/track_supervisor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/stopwatch.hpp"
#include "model/occlusion_chain.hpp"
#include "reference/pose_score.hpp"
#include "search/box_centre_points.hpp"
#include "search/simplify_mesh.hpp"
#include "search/surface_points.hpp"
#include "tracker/confidence_model.hpp"

namespace depthtrack {

namespace {
// Cells of a tenth of the object's radius: 1.3-2.7k of the YCB meshes' 16k triangles remain, the
// scores at the true pose move by 4-15 %, the time per pose falls 3-5 fold (reference, 80x60).
constexpr double kSimplifyCell = 0.1;

// The coarse stages' observation model, tempered: the tracker's own (sigma 3 mm at 0 m, tail
// weight 0.01) is so peaked that a pose one coarse grid step (pixels, 15-20 degrees) from the
// truth can score below a flat wall. Sigma grows to half the grid's translation step and the tail
// weight to kTemperedTail, so such a pose still rises above it (built-in object at 80x60, 10 px
// across: from -75..+18 to +82..+174 against about 90 for the best wall poses).
constexpr double kTemperedTail = 0.1;
constexpr size_t kFewPoints = 48, kFewPointsInBox = 12;
// Candidates fitted by Gauss-Newton before the final ranking without a hint, and the fit's steps.
constexpr size_t kFitted = 8;
// Candidates fitted in a box, and the deeper starts each is fitted from besides its own.
constexpr size_t kFittedInBox = 16;
constexpr int kDeeperSteps = 2;
constexpr size_t kTurnedInBox = 2;
// A detector's box bounds the object's visible pixels. A pose whose own visible pixels (those the
// frame does not see hidden behind something nearer) have a box unlike the given one is not the object
// boxed: one sunk behind a neighbour's surface explains its pixels as occluded and keeps few visible
// (ycbv-0049's bowl: the coarse grid's best-scoring poses overlap the box by 0.15-0.19, the truth by
// 0.92), one slid aside shows them beside the box. The poses compared (the grid's, the fitted ones)
// are gated by their overlap against the best of them (search::AgreementFunction), so a box grown or
// shifted by a detector lowers the floor with the best. The margin leaves the grid's poses near the
// right one, up to half a step (2 working pixels) off, in: on ycbv-0049 0.15 left the bowl only grid
// poses 36-41 mm off, 0.45 let the tuna fish can's 30-38 mm off ones (overlap 0.52-0.57) outrank the
// right ones (0.8); 0.3 finds both.
constexpr double kAgreementMargin = 0.3;
bool disagrees(const search::Candidate& c) {
  return c.score < -0.5 * search::kDisagrees;
}
constexpr int kFitIterations = 16;
// One stage (no refine.fine_noise_scale): the search ranks basins, the filter's own fit then refines
// the pose found.
TrackerConfig fit_config(TrackerConfig config) {
  config.refine.iterations = kFitIterations;
  config.refine.fine_noise_scale = 0;
  return config;
}
ObservationModel tempered(ObservationModel m, double translation_spacing) {
  m.sigma_constant = std::max(m.sigma_constant, 0.5 * translation_spacing);
  m.tail_weight = std::max(m.tail_weight, kTemperedTail);
  return m;
}

std::vector<Eigen::Vector3d> vertices_of(const Mesh& mesh) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) out.push_back(v.cast<double>());
  return out;
}

search::SearchObject search_object(const Mesh& mesh) {
  search::SearchObject o;
  o.centre = mesh.centre().cast<double>();
  o.radius = mesh.radius();
  o.vertices.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) o.vertices.push_back(v.cast<double>());
  return o;
}
}  // namespace

TrackSupervisor::TrackSupervisor(FilterBackend& backend, const Mesh& mesh, const Camera& sensor, const Camera& working,
                                 int decimation, const TrackerConfig& config)
    : config_(config),
      sensor_(sensor),
      working_(working),
      decimation_(decimation),
      object_(search_object(mesh)),
      simplified_(search::simplify_mesh(mesh, kSimplifyCell * mesh.radius())),
      box_points_(vertices_of(simplified_)),
      coarse_(backend.make_pose_scorer(simplified_)),
      full_(backend.make_pose_scorer(mesh)),
      workers_(std::make_unique<SearchWorkers>(mesh, working, config, fit_config(config), search_threads(config))),
      rasterizer_(mesh, working, config.near_plane, config.observation.max_depth),
      scratch_(static_cast<size_t>(working.pixel_count())) {
  // The confidence draws the estimate on the host every frame, after the device's work: a fine mesh's (a
  // YCB model's 16k triangles took 0.5-0.65 ms on one core of the H200's host; the mug simplified to 0.5 mm,
  // 3,196 triangles, about 0.3) is split over a few threads; a coarse one's (the handset's 842: 0.07 ms)
  // is not worth waking them for.
  constexpr size_t kSplitTriangles = 2048;
  constexpr int kSplitThreads = 4;
  if (mesh.triangles.size() >= kSplitTriangles && hardware_threads() > 1)
    rasterizer_.split_over(std::make_shared<ThreadPool>(std::min(kSplitThreads, hardware_threads())));
}

namespace {
// Adds a fit's time to times.fit_ms when it ends, less the scoring and box agreement within it.
class FitTimer {
 public:
  explicit FitTimer(search::SearchTimes& times) : times_(times), before_(times) {}
  FitTimer(const FitTimer&) = delete;
  FitTimer& operator=(const FitTimer&) = delete;
  ~FitTimer() {
    times_.fit_ms += clock_.elapsed_ms() - (times_.scoring_ms - before_.scoring_ms) - (times_.box_ms - before_.box_ms);
  }

 private:
  search::SearchTimes& times_;
  const search::SearchTimes before_;
  const Stopwatch clock_;
};
}  // namespace

std::vector<double> TrackSupervisor::score(PoseScorer& scorer, std::span<const Pose> poses, const DepthImage& working,
                                           const ObservationModel& model) const {
  const Stopwatch clock;
  std::vector<double> out = scorer.score(poses, working, model);
  times_.scoring_ms += clock.elapsed_ms();
  return out;
}

search::SearchSettings TrackSupervisor::settings(const InitHint& hint, double budget_ms, unsigned round,
                                                 bool box_regions) const {
  search::SearchSettings settings;
  settings.budget_ms = budget_ms;
  settings.seed = config_.seed;
  settings.round = round;
  settings.by_region = hint.kind == InitHint::Kind::None || (box_regions && hint.kind == InitHint::Kind::Box);
  // A box holds one object's neighbourhood: its best sparse pairs lie near the object (ycbv-0000's mug: 80,440
  // coarse poses become 25,828, the same pose found).
  settings.two_level = hint.kind == InitHint::Kind::Box;
  settings.agreement_margin = kAgreementMargin;
  return settings;
}

search::SearchResult TrackSupervisor::search(const DepthImage& sensor_depth, const DepthImage& working,
                                             const InitHint& hint, double budget_ms, unsigned round,
                                             bool detector_box) const {
  const search::ImageBox bounds = detector_box ? search::hint_box(hint, decimation_) : search::ImageBox{};
  times_ = {};
  // Every return carries the time spent on both searches.
  const auto timed = [this](search::SearchResult r) {
    r.times = times_;
    return r;
  };
  search::SearchResult result = candidates(sensor_depth, working, hint, budget_ms, round, bounds, false);
  bool supported_apart = false;
  const bool chosen = !result.candidates.empty() && finish(result, working, hint, round, bounds, &supported_apart);
  if (hint.kind != InitHint::Kind::Box || chosen || supported_apart) return timed(std::move(result));
  // No candidate the evidence supports: the box can hold other objects' surfaces too (ycbv-0049's tuna
  // fish can: the right pose's neighbourhood was left out), so every region of it keeps its own. Its
  // result is taken where the evidence chose, or, with a detector's box, where it supports poses apart.
  search::SearchResult wide = candidates(sensor_depth, working, hint, budget_ms, round, bounds, true);
  bool wide_apart = false;
  if (wide.candidates.empty()) return timed(std::move(result));
  const bool wide_chosen = finish(wide, working, hint, round, bounds, &wide_apart);
  if (!wide_chosen && !(wide_apart && !bounds.empty())) return timed(std::move(result));
  wide.coarse_poses += result.coarse_poses;
  wide.poses_scored += result.poses_scored;
  return timed(std::move(wide));
}

search::SearchResult TrackSupervisor::candidates(const DepthImage& sensor_depth, const DepthImage& working,
                                                 const InitHint& hint, double budget_ms, unsigned round,
                                                 const search::ImageBox& bounds, bool box_regions) const {
  const search::SearchSettings settings = this->settings(hint, budget_ms, round, box_regions);
  // Surface points one coarse grid step apart, found in the sensor's pixels (a box may be smaller
  // than one working pixel).
  const int stride = std::max(1, static_cast<int>(std::lround(settings.coarse_pixels * decimation_)));
  std::vector<Eigen::Vector3d> surface = search::surface_points(sensor_depth, sensor_, hint, object_.radius, stride);
  // Few points mean a small object or box: a denser grid, down to one point per working pixel,
  // puts enough of them on it (a box's points lie on or near the object, so fewer suffice).
  const size_t enough = hint.kind == InitHint::Kind::Box ? kFewPointsInBox : kFewPoints;
  for (int s = stride / 2; surface.size() < enough && s >= decimation_; s /= 2)
    surface = search::surface_points(sensor_depth, sensor_, hint, object_.radius, s);
  const double spacing = search::grid_resolution(object_, working_, surface, settings).translation_spacing;
  // A box's middle at the depths seen in it: centres an occluder across the object leaves out.
  const std::vector<Eigen::Vector3d> centres = search::box_centre_points(hint, sensor_, surface, spacing);
  surface.insert(surface.end(), centres.begin(), centres.end());
  const ObservationModel soft = tempered(config_.observation, spacing);
  const search::ScoreFunction coarse = [&](std::span<const Pose> p) { return score(*coarse_, p, working, soft); };
  search::SearchResult result =
      search::global_search(object_, working_, surface, coarse, settings, box_agreement(bounds, working, soft));
  if (result.candidates.empty()) return result;
  // The full mesh and the tracker's own model rank the candidates again.
  const std::vector<Pose> poses = search::poses_of(result.candidates);
  std::vector<double> scores = score(*full_, poses, working, config_.observation);
  gate(poses, scores, bounds, working);
  for (size_t i = 0; i < poses.size(); ++i) result.candidates[i].score = scores[i];
  result.poses_scored += poses.size();
  return result;
}

bool TrackSupervisor::finish(search::SearchResult& result, const DepthImage& working, const InitHint& hint,
                             unsigned round, const search::ImageBox& bounds, bool* supported_apart) const {
  if (hint.kind == InitHint::Kind::None) fit_best(result, working);
  const bool chosen = hint.kind == InitHint::Kind::Box && fit_confident(result, working, bounds, supported_apart);
  // The best few are polished from a quarter of the coarse steps down to a sixteenth.
  const search::AgreementFunction agreement = box_agreement(bounds, working, config_.observation);
  const double floor = agreement
                           ? search::agreement_floor(agreement(search::poses_of(result.candidates)), kAgreementMargin)
                           : -std::numeric_limits<double>::infinity();
  const search::ScoreFunction full = search::gated(
      [&](std::span<const Pose> p) { return score(*full_, p, working, config_.observation); }, agreement, floor);
  const double radians = result.rotation_radius, metres = result.translation_spacing;
  const search::RefineStage polish[] = {
      {radians / 4, metres / 4, 6}, {radians / 8, metres / 8, 4}, {radians / 16, metres / 16, 4}};
  result.candidates = search::refine_candidates(std::move(result.candidates), object_, full, polish,
                                                settings(hint, 0.0, round), &result.poses_scored);
  // The scores handed on are log-likelihoods: of a detector's box, only the candidates that agree with
  // it are kept (where none does, all are, their scores restored).
  if (std::all_of(result.candidates.begin(), result.candidates.end(), disagrees))
    for (search::Candidate& c : result.candidates) c.score += search::kDisagrees;
  else
    std::erase_if(result.candidates, disagrees);
  return chosen;
}

search::AgreementFunction TrackSupervisor::box_agreement(const search::ImageBox& bounds, const DepthImage& working,
                                                         const ObservationModel& model) const {
  if (bounds.empty()) return nullptr;
  return [this, given = bounds, &working, model](std::span<const Pose> poses) {
    const Stopwatch clock;
    std::vector<double> out(poses.size());
    // On a device the coarse scorer projects its mesh's vertices (box_points_) there; else the host's threads.
    const std::vector<float> boxes = coarse_->visible_boxes(poses, working, model, config_.loss.pixel_sigmas);
    if (boxes.size() == 4 * poses.size()) {
      for (size_t i = 0; i < poses.size(); ++i) {
        const float* b = boxes.data() + 4 * i;
        out[i] = search::box_iou(given, search::ImageBox{b[0], b[1], b[2], b[3]});
      }
    } else {
      workers_->each(poses.size(), [&](size_t i) {
        out[i] = search::box_iou(
            given, search::visible_box(box_points_, poses[i], working_, working, model, config_.loss.pixel_sigmas));
      });
    }
    times_.box_ms += clock.elapsed_ms();
    return out;
  };
}

void TrackSupervisor::gate(std::span<const Pose> poses, std::span<double> scores, const search::ImageBox& bounds,
                           const DepthImage& working) const {
  const search::AgreementFunction agreement = box_agreement(bounds, working, config_.observation);
  if (!agreement || poses.empty()) return;
  const std::vector<double> a = agreement(poses);
  search::lower_disagreeing(scores, a, search::agreement_floor(a, kAgreementMargin));
}

// Without a hint the regions' candidates lie a few millimetres and degrees from their optima, and
// there a right pose and another object's best fit score alike (ycbv-0000: the mug's 1177 against
// 1179 with the full model; the truth scores 1247). The refinement's Gauss-Newton fit takes the best
// few to their optima before they are compared.
void TrackSupervisor::fit_best(search::SearchResult& result, const DepthImage& working) const {
  const FitTimer timer(times_);
  std::sort(result.candidates.begin(), result.candidates.end(),
            [](const search::Candidate& a, const search::Candidate& b) { return a.score > b.score; });
  const std::vector<double> fresh(static_cast<size_t>(working_.pixel_count()), model::fresh_occlusion(config_));
  std::vector<Pose> starts;
  for (size_t i = 0; i < std::min(kFitted, result.candidates.size()); ++i) starts.push_back(result.candidates[i].pose);
  const std::vector<Pose> fitted = workers_->fit(starts, working, fresh);
  const std::vector<double> scores = score(*full_, fitted, working, config_.observation);
  result.poses_scored += fitted.size();
  for (size_t i = 0; i < fitted.size(); ++i)
    if (scores[i] > result.candidates[i].score) result.candidates[i] = {fitted[i], scores[i]};
  // A pose fitted onto another object's surface can outscore the truth (ycbv-0000's gelatin box:
  // 1536 against 1419, a flat box on the flat table beside it), but less of its outline sees past
  // its edge: when some fitted candidates pass found()'s outline test, only they go on to the
  // polish. Not its confidence test: the mug's right candidates, a quarter of them occluded, explain
  // 0.73 of their pixels (the wrong ones 0.83).
  const std::vector<SilhouetteShares> shares =
      workers_->shares(search::poses_of(std::span(result.candidates).first(fitted.size())), working);
  std::vector<search::Candidate> outlined;
  for (size_t i = 0; i < fitted.size(); ++i)
    if (shares[i].separated >= config_.loss.found_outline) outlined.push_back(result.candidates[i]);
  if (!outlined.empty()) result.candidates = std::move(outlined);
}

// In a box the pose that explains the most pixels can be the wrong one, and the grid's candidates
// nearest the right one lie nearer the camera than it (the centre is put behind a measured point by
// 2/3 of the object's front reach: short for a can seen tilted). The best candidates are fitted by
// Gauss-Newton from where they are and from one and two translation steps deeper along the view
// ray. When the fitted poses the evidence supports (confidence at least loss.lost_below, kPlanePixels
// seen) all lie together, only they go on to the polish and seed the filter; poses it supports far
// apart (the bowl of ycbv-0049 before the box's agreement: one 5 mm off, one 29 mm) leave the ranking to
// the likelihood: of all candidates, or with a detector's box of the supported ones alone, which the
// box has gated (the bowl from a box shifted right by 15 %: supported poses 7 and 55 mm off, while a
// pose 26 mm off that the evidence does not support scored highest).
bool TrackSupervisor::fit_confident(search::SearchResult& result, const DepthImage& working,
                                    const search::ImageBox& bounds, bool* supported_apart) const {
  const FitTimer timer(times_);
  std::sort(result.candidates.begin(), result.candidates.end(),
            [](const search::Candidate& a, const search::Candidate& b) { return a.score > b.score; });
  if (result.candidates.size() > kFittedInBox) result.candidates.resize(kFittedInBox);
  const std::vector<double> fresh(static_cast<size_t>(working_.pixel_count()), model::fresh_occlusion(config_));
  std::vector<Pose> starts;
  for (const search::Candidate& c : result.candidates)
    for (int step = 0; step <= kDeeperSteps; ++step) {
      Pose start = c.pose;
      start.translation += step * result.translation_spacing * start.apply(object_.centre).normalized();
      starts.push_back(start);
    }
  // The best two turned a quarter, a half and three quarters about the view ray through the centre: a
  // face seen head-on shows the depth its outline alone, which the coarse grid's rotations can miss by a
  // quarter turn (the gelatin box of ycbv-0000 at 80x60: 90 degrees off, ADD-S 3.9 mm).
  for (size_t i = 0; i < std::min(result.candidates.size(), kTurnedInBox); ++i) {
    const Pose& c = result.candidates[i].pose;
    const Eigen::Vector3d centre = c.apply(object_.centre);
    for (int quarter = 1; quarter <= 3; ++quarter) {
      const Eigen::Quaterniond turn(Eigen::AngleAxisd(quarter * M_PI / 2, centre.normalized()));
      Pose turned;
      turned.rotation = turn * c.rotation;
      turned.translation = centre - turned.rotation * object_.centre;
      starts.push_back(turned);
    }
  }
  const std::vector<Pose> fitted = workers_->fit(starts, working, fresh);
  std::vector<double> scores = score(*full_, fitted, working, config_.observation);
  gate(fitted, scores, bounds, working);
  result.poses_scored += fitted.size();
  const std::vector<SilhouetteShares> shares = workers_->shares(fitted, working);
  std::vector<search::Candidate> supported;
  for (size_t i = 0; i < fitted.size(); ++i) {
    const SilhouetteShares& s = shares[i];
    // A pose seen by a few pixels has its evidence fitted as well by a wrong one (the handset behind a 90 %
    // occluder: 5-9 pixels at 80x60): only poses seen by as many as the relief needs are chosen by it.
    const double seen = seen_pixels(s);
    if (seen >= static_cast<double>(kPlanePixels) && pose_confidence(s) >= config_.loss.lost_below)
      supported.push_back({fitted[i], scores[i]});
  }
  const auto apart = [&](const search::Candidate& a, const search::Candidate& b) {
    return (a.pose.apply(object_.centre) - b.pose.apply(object_.centre)).norm() > result.translation_spacing;
  };
  for (const search::Candidate& a : supported)
    for (const search::Candidate& b : supported)
      if (apart(a, b)) {
        if (supported_apart) *supported_apart = true;
        if (!bounds.empty()) result.candidates = std::move(supported);
        return false;
      }
  if (supported.empty()) return false;
  result.candidates = std::move(supported);
  return true;
}

InitHint TrackSupervisor::around(const Pose& pose) const {
  double u0 = sensor_.width, v0 = sensor_.height, u1 = 0, v1 = 0;
  for (const Eigen::Vector3d& vertex : object_.vertices) {
    const Eigen::Vector3d p = pose.apply(vertex);
    if (!(p.z() > config_.near_plane)) return InitHint::anywhere();
    const Eigen::Vector2d uv = sensor_.project(p);
    u0 = std::min(u0, uv.x());
    v0 = std::min(v0, uv.y());
    u1 = std::max(u1, uv.x());
    v1 = std::max(v1, uv.y());
  }
  const double du = 0.5 * (u1 - u0), dv = 0.5 * (v1 - v0);
  u0 -= du, u1 += du, v0 -= dv, v1 += dv;
  if (u1 < 0 || v1 < 0 || u0 > sensor_.width - 1 || v0 > sensor_.height - 1) return InitHint::anywhere();
  auto pixel = [](double x, int size) { return std::clamp(static_cast<int>(std::lround(x)), 0, size - 1); };
  return InitHint::box(pixel(u0, sensor_.width), pixel(v0, sensor_.height), pixel(u1, sensor_.width),
                       pixel(v1, sensor_.height));
}

std::vector<Pose> TrackSupervisor::seeds(const search::SearchResult& result) {
  std::vector<Pose> out;
  if (result.candidates.empty()) return out;
  // Runners-up within a tenth of the best score (log-likelihoods are positive where the object
  // fits) get particles too; the next frames' weights decide among them.
  const double best = result.candidates.front().score;
  for (const auto& c : result.candidates)
    if (out.size() < 4 && c.score >= best - 0.1 * std::abs(best)) out.push_back(c.pose);
  return out;
}

std::vector<Pose> TrackSupervisor::supported_seeds(const search::SearchResult& result, const DepthImage& working) {
  std::vector<Pose> out;
  for (const Pose& p : seeds(result))
    if (pose_confidence(assess(p, working)) >= config_.loss.lost_below) out.push_back(p);
  return out;
}

SilhouetteShares TrackSupervisor::assess(const Pose& pose, const DepthImage& working, const std::vector<float>* drawn) {
  drawn_.reset();  // until the rendering is done
  SilhouetteShares shares;
  if (drawn && drawn->size() == scratch_.size()) {
    std::copy(drawn->begin(), drawn->end(), scratch_.begin());  // silhouette() hands it out
    const reference::PixelBox whole{0, 0, working.width(), working.height()};
    shares = silhouette_shares(scratch_, whole, config_.observation, config_.loss.pixel_sigmas, working);
  } else {
    shares = silhouette_shares(rasterizer_, config_.observation, config_.loss.pixel_sigmas, pose, working, scratch_);
  }
  drawn_ = pose;
  return shares;
}

namespace {
bool same_pose(const Pose& a, const Pose& b) {
  return a.translation == b.translation && a.rotation.coeffs() == b.rotation.coeffs();
}
}  // namespace

const std::vector<float>& TrackSupervisor::silhouette(const Pose& pose) {
  if (!drawn_ || !same_pose(*drawn_, pose)) {
    drawn_.reset();
    rasterizer_.render(pose, scratch_);
    drawn_ = pose;
  }
  return scratch_;
}

bool TrackSupervisor::found(const Pose& pose, const DepthImage& working) {
  const SilhouetteShares s = assess(pose, working);
  return pose_confidence(s) >= config_.loss.found_above && s.separated >= config_.loss.found_outline;
}

TrackSupervisor::Verdict TrackSupervisor::observe(const PoseEvidence& evidence, double time_s) {
  // A pose the evidence does not support is never reported as tracked: lost at once. The filter can
  // find the object again by itself (an occluder moves away), which ends it just as at once.
  const RunConfidence::Reading reading = run_.update(evidence, time_s, config_.loss.lost_below);
  lost_frames_ = reading.frame < config_.loss.lost_below ? lost_frames_ + 1 : 0;
  status_ = lost_frames_ > 0 ? TrackStatus::Lost : TrackStatus::Tracking;
  return {reading.reported, reading.frame, status_};
}

bool TrackSupervisor::should_search() const {
  return status_ == TrackStatus::Lost && lost_frames_ >= config_.loss.search_after;
}

void TrackSupervisor::reset() {
  status_ = TrackStatus::Tracking;
  lost_frames_ = 0;
  run_.end_run();
}

}  // namespace depthtrack
