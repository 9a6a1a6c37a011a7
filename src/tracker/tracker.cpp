#include <algorithm>
#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/mesh_simplify.hpp"
#include "core/stopwatch.hpp"
#include "core/timestamp_limits.hpp"
#include "model/covariance_calibration.hpp"
#include "model/fit_noise.hpp"
#include "tracker/confidence_model.hpp"
#include "tracker/make_filter_backend.hpp"
#include "tracker/particle_budget.hpp"
#include "tracker/residual_structure.hpp"
#include "tracker/track_supervisor.hpp"
#include "tracker/tracker_impl.hpp"

namespace depthtrack {

namespace {
// Particle spread around search candidates: the search's last steps are finer than this, the
// filter's first frames settle the rest.
constexpr InitialSpread kSearchSpread{0.005, 0.05};

// Poses a device's prime scores at once (at most the configuration's particles): a GPU scorer's batch,
// one launch (DevicePoseScorer).
constexpr int kDevicePrimePoses = 4096;

// One particle's time for a frame budget's first frame (ParticleBudget::prime): twice the least of a few
// drawings and weighings of the start pose against a depth image that sees the object's centre depth
// at every pixel, so that every pixel drawn is weighed. Twice: the filter's weighing also keeps each
// pixel's occlusion state, and its first frame touches its memory first (the YCB mug's first frame
// measured 0.1 ms a particle, this score 0.04). On a device one pose's scoring is the launches' and the
// transfers' time, not a particle's (a GPU draws thousands side by side in about the same time), so
// `poses` copies are scored at once and the time divided among them: still more than a particle's on a
// GPU (the budget's frames then correct it upwards), never less.
double particle_time_ms(FilterBackend& backend, const Camera& working, const Pose& pose, const Eigen::Vector3d& centre,
                        const ObservationModel& model, int poses) {
  const float z = static_cast<float>(pose.apply(centre).z());
  const DepthImage flat = DepthImage::from_metres(working.width, working.height,
                                                  std::vector<float>(static_cast<size_t>(working.pixel_count()), z));
  const std::vector<Pose> scored(static_cast<size_t>(poses), pose);
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const Stopwatch clock;
    backend.score_poses(scored, flat, model);
    least = std::min(least, clock.elapsed_ms());
  }
  return 2 * least / poses;
}

// The most steps a frame's fit can take: `iterations` in each of its stages (model::fit_stages).
int most_fit_steps(const TrackerConfig& config) {
  if (!config.refine.enabled) return 0;
  return config.refine.iterations * static_cast<int>(model::fit_stages(config).size());
}

void add_search_times(StepTimings& timings, const search::SearchTimes& times) {
  timings.search_scoring_ms += times.scoring_ms;
  timings.search_box_ms += times.box_ms;
  timings.search_fit_ms += times.fit_ms;
}

bool is_finite(const Estimate& e) {
  return e.pose.translation.allFinite() && e.pose.rotation.coeffs().allFinite() && e.linear_velocity.allFinite() &&
         e.angular_velocity.allFinite() && std::isfinite(e.effective_sample_size);
}
}  // namespace

const char* to_string(TrackStatus status) {
  switch (status) {
    case TrackStatus::Tracking:
      return "tracking";
    case TrackStatus::Lost:
      return "lost";
    case TrackStatus::NoData:
      return "no-data";
  }
  return "?";
}

Tracker::Tracker(const Mesh& mesh, const Camera& sensor, const TrackerConfig& config) {
  sensor.validate();
  config.validate();
  // Checked before the device opens, so that a bad mesh or resolution is reported as such.
  Mesh checked = mesh;
  checked.validate_and_clean("tracker mesh");
  sensor.decimation_factor_for(config.width, config.height);
  impl_ = std::make_unique<Impl>(open_config_device(config), sensor, checked, config);
}

Tracker::Tracker(std::shared_ptr<Device> device, const Mesh& mesh, const Camera& sensor, const TrackerConfig& config) {
  if (!device) throw InputError("tracker device is null: open one with Device::open");
  sensor.validate();
  TrackerConfig on_device = config;
  on_device.backend = device->selector();
  on_device.validate();
  Mesh checked = mesh;
  checked.validate_and_clean("tracker mesh");
  impl_ = std::make_unique<Impl>(std::move(device), sensor, checked, on_device);
}

Tracker::~Tracker() = default;
Tracker::Tracker(Tracker&&) noexcept = default;
Tracker& Tracker::operator=(Tracker&&) noexcept = default;

void Tracker::initialize(const Pose& pose, const InitialSpread& spread) {
  impl_->initialize(pose, spread);
}
Estimate Tracker::initialize_global(const DepthImage& depth, double timestamp, const InitHint& hint) {
  return impl_->initialize_global(depth, timestamp, hint);
}
Estimate Tracker::update(const DepthImage& depth, double timestamp) {
  if (!impl_->initialized_) throw InputError("Tracker::update called before initialize()");
  DepthImage storage;
  const DepthImage& working = impl_->working_frame(depth, storage);
  return impl_->track_frame(
      working, [&depth]() -> const DepthImage& { return depth; }, timestamp);
}
void Tracker::set_particle_count(int count) {
  impl_->set_particle_count(count);
}
const Camera& Tracker::working_camera() const {
  return impl_->working_;
}
const TrackerConfig& Tracker::config() const {
  return impl_->config_;
}
std::pair<int, int> Tracker::occlusion_window_size() const {
  return impl_->backend_->occlusion_window_size();
}
std::string Tracker::backend_description() const {
  return impl_->backend_->description();
}
size_t Tracker::mesh_triangles() const {
  return impl_->mesh_triangles_;
}
size_t Tracker::drawn_triangles() const {
  return impl_->drawn_triangles_;
}

Tracker::Impl::Impl(std::shared_ptr<Device> device, const Camera& sensor, const Mesh& checked,
                    const TrackerConfig& config)
    : device_(std::move(device)),
      sensor_(sensor),
      decimation_(sensor.decimation_factor_for(config.width, config.height)),
      working_(sensor.decimated(decimation_)),
      config_(config) {
  centre_ = checked.centre().cast<double>();
  symmetry_ = symmetry_axis(checked);
  if (symmetry_) held_turn_.emplace(*symmetry_, config.motion);
  // Every rendering draws the simplified mesh (the given one when simplify_error is 0); a frame budget
  // draws a fine one coarser (simplify_for_budget).
  const MeshSimplification drawn = config.budget_ms > 0 ? simplify_for_budget(checked, config.simplify_error)
                                                        : simplify_for_drawing(checked, config.simplify_error);
  mesh_triangles_ = checked.triangles.size();
  drawn_triangles_ = drawn.mesh.triangles.size();
  // A budget on a device times the filter's steps there: its model needs the particle loops' share of
  // the frame (ParticleBudget::observe), which a device reports only from its steps' timing records.
  TrackerConfig filter_config = config;
  if (config.budget_ms > 0 && !device_->is_host()) filter_config.step_timings = true;
  backend_ = make_filter_backend(*device_, drawn.mesh, working_, filter_config);
  supervisor_ = std::make_unique<TrackSupervisor>(*backend_, drawn.mesh, sensor_, working_, decimation_, config);
  particle_count_ = config.particles;
  if (config.budget_ms > 0)
    budget_ = std::make_unique<ParticleBudget>(config.budget_ms, config.min_particles, config.particles,
                                               config.loss.lost_below, config.motion, most_fit_steps(config));
}

int Tracker::Impl::prime_poses() const {
  return device_->is_host() ? 1 : std::min(config_.particles, kDevicePrimePoses);
}

void Tracker::Impl::set_particle_count(int count) {
  if (budget_) throw InputError("set_particle_count: the frame budget (budget_ms) chooses the particle count");
  backend_->set_particle_count(count);
  particle_count_ = count;
}

void Tracker::Impl::choose_particle_count(bool reseed) {
  if (!budget_) return;
  const int count = budget_->next(reseed);
  backend_->set_particle_count(count);
  particle_count_ = count;
}

void Tracker::Impl::initialize(const Pose& pose, const InitialSpread& spread) {
  if (!pose.translation.allFinite() || !pose.rotation.coeffs().allFinite())
    throw InputError("initial pose is not finite");
  // A zero quaternion is no rotation at all (its rows would read q = 0); any other is normalized.
  const double norm = pose.rotation.norm();
  if (!(norm > 1e-9)) throw InputError("initial rotation is a zero quaternion (qw qx qy qz all 0)");
  Pose start = pose;
  start.rotation.normalize();
  // The object must start where the camera can see it: its centre in front, within max_depth.
  const double depth = (start.rotation * centre_ + start.translation).z();
  if (!(depth >= config_.near_plane && depth <= config_.observation.max_depth)) {
    std::ostringstream m;
    m << "initial pose puts the object's centre at depth z = " << depth << " m, "
      << (depth < config_.near_plane ? "behind or too close to the camera" : "beyond max depth") << ": it must be in ["
      << config_.near_plane << ", " << config_.observation.max_depth << "] m";
    throw InputError(m.str());
  }
  // Wider than the depth range or a full turn, the cloud says nothing about where the object is.
  if (!(std::isfinite(spread.metres) && spread.metres >= 0 && spread.metres <= config_.observation.max_depth &&
        std::isfinite(spread.radians) && spread.radians >= 0 && spread.radians <= 2 * std::numbers::pi)) {
    std::ostringstream m;
    m << "initial spread " << spread.metres << " m, " << spread.radians
      << " rad must be finite and non-negative, at most max depth (" << config_.observation.max_depth
      << " m) and a full turn (2 pi rad)";
    throw InputError(m.str());
  }
  if (budget_ && !budget_->timed())
    budget_->prime(particle_time_ms(*backend_, working_, start, centre_, config_.observation, prime_poses()));
  // The first frame's weighing searches the spread for the pose: a search's budget, not a frame's.
  if (budget_) {
    const int count = budget_->next_initial(config_.recovery.budget_ms);
    backend_->set_particle_count(count);
    particle_count_ = count;
  }
  backend_->initialize(start, spread);
  supervisor_->reset();
  if (held_turn_) held_turn_->reset();
  search_candidates_.clear();
  initialized_ = true;
  has_previous_ = false;
  gap_pending_ = false;
  frames_since_initialize_ = 0;
}

const DepthImage& Tracker::Impl::working_frame(const DepthImage& depth, DepthImage& storage) const {
  if (depth.width() != sensor_.width || depth.height() != sensor_.height) {
    std::ostringstream m;
    m << "depth image is " << depth.width() << "x" << depth.height() << " but the camera is " << sensor_.width << "x"
      << sensor_.height;
    throw InputError(m.str());
  }
  // Decimate only when needed: at the sensor's resolution the caller's image is used as it is.
  const DepthImage* working = &depth;
  if (decimation_ > 1) {
    storage = depth.decimated(decimation_);
    working = &storage;
  }
  // Depths beyond max_depth are outside the observation model (its uniform tail ends there, and far
  // readings would overflow it): they count as missing. Copied only when some pixel is that deep.
  const float max_depth = static_cast<float>(config_.observation.max_depth);
  const auto& data = working->data();
  if (std::none_of(data.begin(), data.end(), [&](float z) { return z > max_depth; })) return *working;
  DepthImage kept(working->width(), working->height());
  for (int v = 0; v < kept.height(); ++v)
    for (int u = 0; u < kept.width(); ++u)
      if (working->at(u, v) <= max_depth) kept.at(u, v) = working->at(u, v);
  storage = std::move(kept);
  return storage;
}

Estimate Tracker::Impl::initialize_global(const DepthImage& depth, double timestamp, const InitHint& hint) {
  check_timestamp(timestamp);
  DepthImage storage;
  const DepthImage& working = working_frame(depth, storage);
  const Stopwatch clock;
  // The caller's box is a detector's: it bounds the object's visible pixels.
  const search::SearchResult found = supervisor_->search(depth, working, hint, 0.0, 0u, true);
  if (found.candidates.empty())
    throw InputError(
        "global initialization: nothing in the frame stands out in front of its surroundings by half the "
        "object's size; give a box or a point");
  search_candidates_.clear();
  for (const search::Candidate& c : found.candidates)
    search_candidates_.push_back({c.pose, c.score, pose_confidence(supervisor_->assess(c.pose, working))});
  const std::vector<Pose> seeds = TrackSupervisor::seeds(found);
  if (budget_ && !budget_->timed())
    budget_->prime(particle_time_ms(*backend_, working_, seeds.front(), centre_, config_.observation, prime_poses()));
  choose_particle_count(true);
  backend_->initialize_modes(seeds, kSearchSpread);
  const double search_ms = clock.elapsed_ms();
  supervisor_->reset();
  if (held_turn_) held_turn_->reset();
  initialized_ = true;
  has_previous_ = false;
  gap_pending_ = false;
  frames_since_initialize_ = 0;
  Estimate e = run_frame(working, timestamp);
  e.timings.search_ms += search_ms;
  e.timings.total_ms += search_ms;
  add_search_times(e.timings, found.times);
  e.search_poses = found.poses_scored;
  return e;
}

Estimate Tracker::Impl::track_frame(const DepthImage& working, const std::function<const DepthImage&()>& sensor_frame,
                                    double timestamp) {
  start_frame(working, sensor_frame, timestamp);
  return finish_frame(working);
}

void Tracker::Impl::start_frame(const DepthImage& working, const std::function<const DepthImage&()>& sensor_frame,
                                double timestamp) {
  check_timestamp(timestamp);
  if (has_previous_ && timestamp <= previous_timestamp_) {
    std::ostringstream m;
    m.precision(17);
    m << "timestamps must increase: " << timestamp << " s follows " << previous_timestamp_ << " s";
    throw InputError(m.str());
  }
  // After a gap the motion model cannot bridge (max_time_step) the particles are drawn anew around the
  // last pose, and, unless this frame still supports that pose, around those best candidates of a search
  // near it that the evidence supports: the next frames' weights decide among them, and the confidence
  // says when the track holds again. While lost for a few frames, the whole frame is searched; a candidate the depth
  // supports re-seeds the filter. A dropout frame has nothing to search.
  PendingFrame search;
  gap_pending_ = gap_pending_ || (has_previous_ && timestamp - previous_timestamp_ > config_.max_time_step);
  const bool gap = gap_pending_;
  if (gap) supervisor_->end_run();
  choose_particle_count(gap || (config_.recovery.enabled && supervisor_->should_search()));
  if (config_.recovery.enabled && working.valid_count() > 0 && (gap || supervisor_->should_search())) {
    gap_pending_ = false;
    const Stopwatch clock;
    const bool holds = gap && pose_confidence(supervisor_->assess(last_pose_, working)) >= config_.loss.lost_below;
    search::SearchResult found;
    if (!holds)
      found = supervisor_->search(sensor_frame(), working, gap ? supervisor_->around(last_pose_) : InitHint::anywhere(),
                                  config_.recovery.budget_ms, ++search_round_);
    if (gap) {
      std::vector<Pose> modes{last_pose_};
      for (const Pose& p : supervisor_->supported_seeds(found, working)) modes.push_back(p);
      backend_->initialize_modes(modes, kSearchSpread);
      has_previous_ = false;
      search.recovered = true;
    } else if (!found.candidates.empty() && supervisor_->found(found.candidates.front().pose, working)) {
      backend_->initialize_modes(TrackSupervisor::seeds(found), kSearchSpread);
      supervisor_->reset();
      if (held_turn_) held_turn_->reset();
      has_previous_ = false;
      search.recovered = true;
    }
    search.search_ms = clock.elapsed_ms();
    search.search_times = found.times;
    search.search_poses = found.poses_scored;
  }
  enqueue_frame(working, timestamp);
  pending_.recovered = search.recovered;
  pending_.search_ms = search.search_ms;
  pending_.search_times = search.search_times;
  pending_.search_poses = search.search_poses;
}

Estimate Tracker::Impl::run_frame(const DepthImage& working, double timestamp) {
  enqueue_frame(working, timestamp);
  return finish_frame(working);
}

void Tracker::Impl::enqueue_frame(const DepthImage& working, double timestamp) {
  if (frame_pending_) throw InputError("tracker: a frame was started while the previous one is not finished");
  // A gap longer than max_time_step is propagated as that long (TrackerConfig says why).
  const double dt = has_previous_ ? std::min(timestamp - previous_timestamp_, config_.max_time_step) : 0.0;
  backend_->enqueue_update(working, dt);
  pending_ = PendingFrame{};
  pending_.timestamp = timestamp;
  frame_pending_ = true;
}

Estimate Tracker::Impl::finish_frame(const DepthImage& working) {
  Estimate e = collect_frame();
  assess_frame(e, working);
  return e;
}

Estimate Tracker::Impl::collect_frame() {
  if (!frame_pending_) throw InputError("tracker: finish_frame() without a started frame");
  frame_pending_ = false;
  const double timestamp = pending_.timestamp;
  Estimate e = backend_->collect();
  e.particles = particle_count_;
  e.recovered = pending_.recovered;
  e.search_poses = pending_.search_poses;
  e.timings.search_ms += pending_.search_ms;
  e.timings.total_ms += pending_.search_ms;
  add_search_times(e.timings, pending_.search_times);
  if (!is_finite(e)) {
    std::ostringstream m;
    m.precision(17);
    m << "frame " << frames_since_initialize_ << " (at " << timestamp
      << " s): the estimate is not finite; the input or the configuration is outside what the model handles";
    throw InputError(m.str());
  }
  previous_timestamp_ = timestamp;
  has_previous_ = true;
  last_pose_ = e.pose;
  ++frames_since_initialize_;
  return e;
}

void Tracker::Impl::assess_frame(Estimate& e, const DepthImage& working) {
  const Eigen::Matrix<double, 6, 6> fit_covariance = e.covariance;  // the fit's, before the report calibrates it
  const double frame_confidence = assess_confidence(e, working);
  // The budget follows how hard this frame is: its own evidence, not the run's confidence.
  if (budget_) budget_->observe(e, fit_covariance, frame_confidence);
}

double Tracker::Impl::assess_confidence(Estimate& e, const DepthImage& working) {
  // A dropout: every pixel adds 0 to every particle's log-likelihood, so the weights stay as they
  // are and resampling, decided on them, cannot trigger: the filter propagates only.
  if (working.valid_count() == 0) {
    // Nothing was seen: no evidence for or against the track, so the loss hysteresis is left alone.
    e.confidence = 0;
    e.status = TrackStatus::NoData;
    hold_turn(e, std::numeric_limits<double>::infinity());  // the propagation tells nothing of the turn
    return 0.0;
  }
  const Stopwatch clock;
  const std::vector<float>* drawn = backend_->rendering_of(e.pose);
  e.evidence = supervisor_->assess(e.pose, working, drawn);
  const ResidualStructure residual = residual_structure(drawn ? *drawn : supervisor_->silhouette(e.pose),
                                                        config_.observation, config_.loss.pixel_sigmas, working);
  // collect_frame() has made this frame's timestamp the previous one.
  const TrackSupervisor::Verdict verdict = supervisor_->observe(e.evidence, previous_timestamp_);
  e.confidence = verdict.confidence;
  e.status = verdict.status;
  hold_turn(e, report_covariance(e, residual));
  e.timings.confidence_ms = clock.elapsed_ms();
  e.timings.total_ms += e.timings.confidence_ms;
  return verdict.frame_confidence;
}

double Tracker::Impl::report_covariance(Estimate& e, const ResidualStructure& residual) const {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  if (e.covariance.array().isNaN().any()) return kNone;  // refinement off, or too few pixels for the fit
  // Lost, or too little of the silhouette agrees with the pose: the depth does not determine it.
  if (e.status == TrackStatus::Lost || e.evidence.visible < model::kLeastVisibleShare) {
    e.covariance = model::undetermined_covariance();
    return std::numeric_limits<double>::infinity();
  }
  // The fit's covariance scaled by what the residual at the estimate says, the principal point's
  // sideways shift added, and a turn about the mesh's axis of symmetry left undetermined
  // (model/covariance_calibration.hpp).
  e.covariance =
      model::calibrated_covariance(e.covariance, residual.white, residual.smooth(), residual.pixels, working_.width);
  e.covariance = model::with_principal_point(e.covariance, e.pose.apply(centre_).z(), sensor_.fx);
  if (!symmetry_) return kNone;
  // A turn about the axis (through symmetry_->point) as a twist about the centre: the centre moves by
  // axis x (centre - point), both in the camera frame.
  const Eigen::Vector3d axis = e.pose.rotation * symmetry_->direction;
  const double variance = turn_variance(e.covariance, axis);
  Eigen::Matrix<double, 6, 1> turn;
  turn << axis.cross(e.pose.rotation * (centre_ - symmetry_->point)), axis;
  e.covariance = model::with_undetermined_direction(e.covariance, turn);
  return variance;
}

void Tracker::Impl::hold_turn(Estimate& e, double turn_variance) {
  if (!held_turn_) return;
  if (e.status == TrackStatus::Lost) {
    held_turn_->reset();
    return;
  }
  // collect_frame() has made this frame's timestamp the previous one.
  e.pose = held_turn_->report(e.pose, turn_variance, seen_pixels(e.evidence), previous_timestamp_);
}

const std::vector<float>& Tracker::Impl::silhouette(const Pose& pose) {
  return supervisor_->silhouette(pose);
}

}  // namespace depthtrack
