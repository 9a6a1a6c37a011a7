#include "filter/device_filter.hpp"

#include <cmath>
#include <depthtrack/error.hpp>
#include <numeric>
#include <sstream>

#include "compute/kernel_sources.hpp"
#include "core/stopwatch.hpp"
#include "dt_state.h"
#include "filter/device_pose_scorer.hpp"
#include "filter/model_args.hpp"
#include "filter/particle_packing.hpp"
#include "philox.h"
#include "reference/occlusion_chain.hpp"

namespace depthtrack {

namespace {
constexpr size_t kGroupSize = 128;   // work-items per group in weigh, summarize and the gathers
constexpr size_t kLinearGroup = 64;  // work-items per group in the per-particle kernels

// Host mirror of the struct cl/propagate.cl takes by value.
struct MotionArgs {
  float keep, linear_std, angular_std, dt, centre_x, centre_y, centre_z;
};
struct RefineArgs {  // cl/refine.cl's dt_refine_args
  float damping, min_incidence, centre_x, centre_y, centre_z, now;
  int iterations;
};
struct InitialArgs {  // cl/initialize.cl's dt_initial
  float metres, radians, centre_x, centre_y, centre_z;
  unsigned mode_count;
};

size_t round_up(size_t n, size_t multiple) {
  return (n + multiple - 1) / multiple * multiple;
}

int occlusion_define(OcclusionStorage mode) {
  switch (mode) {
    case OcclusionStorage::PerPixelTime:
      return 0;
    case OcclusionStorage::GlobalTime:
      return 1;
    case OcclusionStorage::Off:
      return 2;
  }
  return 2;
}
}  // namespace

struct DeviceFilter::Kernels {
  std::unique_ptr<compute::Program> propagate_program, weigh_program, summarize_program, resample_program,
      refine_program, initialize_program;
  std::unique_ptr<compute::Kernel> propagate, weigh, summarize, prefix_sum, find_parents, gather_state, gather_pixels,
      fill, refine, shift_particles, initialize_particles, fill_per_particle;
};

DeviceFilter::DeviceFilter(std::unique_ptr<compute::Queue> queue, const Mesh& mesh, const Camera& camera,
                           const TrackerConfig& config)
    : queue_(std::move(queue)),
      config_(config),
      camera_(camera),
      centre_(mesh.centre().cast<double>()),
      pixels_(static_cast<size_t>(camera.pixel_count())),
      count_(checked_particle_count()),
      atlas_source_(make_atlas_source(*queue_, mesh, camera, config)),
      mesh_(mesh) {
  const std::vector<std::string> defines = {
      "DT_GROUP_SIZE=" + std::to_string(kGroupSize),
      "DT_OCCLUSION=" + std::to_string(occlusion_define(config.occlusion_storage))};
  kernels_ = std::make_unique<Kernels>();
  Kernels& k = *kernels_;
  k.propagate_program = queue_->build("propagate.cl", compute::kernel_source("propagate.cl"), defines);
  k.weigh_program = queue_->build("weigh.cl", compute::kernel_source("weigh.cl"), defines);
  k.summarize_program = queue_->build("summarize.cl", compute::kernel_source("summarize.cl"), defines);
  k.resample_program = queue_->build("resample.cl", compute::kernel_source("resample.cl"), defines);
  k.propagate = k.propagate_program->kernel("propagate");
  k.weigh = k.weigh_program->kernel("weigh");
  k.summarize = k.summarize_program->kernel("summarize");
  k.prefix_sum = k.resample_program->kernel("prefix_sum");
  k.find_parents = k.resample_program->kernel("find_parents");
  k.gather_state = k.resample_program->kernel("gather_state");
  k.gather_pixels = k.resample_program->kernel("gather_pixels");
  k.fill = k.resample_program->kernel("fill");
  if (config.refine.enabled) {
    k.refine_program = queue_->build("refine.cl", compute::kernel_source("refine.cl"), defines);
    k.refine = k.refine_program->kernel("refine");
    k.shift_particles = k.refine_program->kernel("shift_particles");
  }
  k.initialize_program = queue_->build("initialize.cl", compute::kernel_source("initialize.cl"), defines);
  k.initialize_particles = k.initialize_program->kernel("initialize_particles");
  k.fill_per_particle = k.initialize_program->kernel("fill_per_particle");

  compute::Queue& q = *queue_;
  state_ = compute::Buffer<float>(q, count_ * DT_STATE_STRIDE);
  scratch_state_ = compute::Buffer<float>(q, count_ * DT_STATE_STRIDE);
  log_weight_ = compute::Buffer<float>(q, count_);
  log_likelihood_ = compute::Buffer<float>(q, count_);
  weights_ = compute::Buffer<float>(q, count_);
  cumulative_ = compute::Buffer<float>(q, 2 * count_);  // float-float pairs
  parents_ = compute::Buffer<unsigned>(q, count_);
  estimate_ = compute::Buffer<float>(q, DT_EST_SIZE);
  atlas_ = compute::Buffer<float>(q, atlas_source_->layout().floats());
  observed_ = compute::Buffer<float>(q, pixels_);
  // Kernels always take the occlusion buffers; modes that do not use one get a single element.
  const bool occlusion = config.occlusion_storage != OcclusionStorage::Off;
  const bool times = config.occlusion_storage == OcclusionStorage::PerPixelTime;
  occlusion_ = compute::Buffer<float>(q, occlusion ? count_ * pixels_ : 1);
  scratch_occlusion_ = compute::Buffer<float>(q, occlusion ? count_ * pixels_ : 1);
  occlusion_time_ = compute::Buffer<float>(q, times ? count_ * pixels_ : 1);
  scratch_occlusion_time_ = compute::Buffer<float>(q, times ? count_ * pixels_ : 1);
  if (config.refine.enabled) {
    refine_mesh_ = std::make_unique<MeshBuffers>(q, mesh);
    refine_pose_ = compute::Buffer<float>(q, DT_STATE_STRIDE);
    correction_ = compute::Buffer<float>(q, 6);
    refine_tile_ = compute::Buffer<unsigned>(q, pixels_);
    refine_ids_ = compute::Buffer<unsigned>(q, pixels_);
  }
}

DeviceFilter::~DeviceFilter() = default;

size_t DeviceFilter::checked_particle_count() const {
  const size_t count = static_cast<size_t>(config_.particles);
  const bool occlusion = config_.occlusion_storage != OcclusionStorage::Off;
  const bool times = config_.occlusion_storage == OcclusionStorage::PerPixelTime;
  // Atlas, occlusion probabilities and times, each with a resampling twin, plus per-particle state;
  // GL's colour and depth pages and its pose buffer sit on the same GPU.
  const bool gl = config_.renderer == Renderer::Gl && queue_->info().is_gpu;
  const double per_particle =
      4.0 * (static_cast<double>(pixels_) * (1 + (occlusion ? 2 : 0) + (times ? 2 : 0) + (gl ? 2 : 0)) +
             (2 + (gl ? 1 : 0)) * DT_STATE_STRIDE + 6);
  const double needed = per_particle * static_cast<double>(count);
  const auto& info = queue_->info();
  if (info.global_memory > 0 && needed > 0.9 * static_cast<double>(info.global_memory)) {
    std::ostringstream m;
    m.precision(3);
    m << config_.particles << " particles at " << camera_.width << "x" << camera_.height << " need "
      << needed / (1 << 30) << " GiB of device memory but " << info.name << " has "
      << static_cast<double>(info.global_memory) / (1 << 30) << " GiB; at most about "
      << static_cast<long long>(0.9 * static_cast<double>(info.global_memory) / per_particle) << " particles fit";
    throw InputError(m.str());
  }
  return count;
}

std::string DeviceFilter::description() const {
  const auto& info = queue_->info();
  return info.selector + " " + info.name + " (" + info.platform + "); atlas: " + atlas_source_->description();
}

void DeviceFilter::upload_particles(const std::vector<reference::ParticleState>& particles) {
  state_.upload(pack_particles(particles));
}

// Drawn and filled on the device (cl/initialize.cl) with the reference's draws: start-up holds no
// host copy of the particles or of their particles x pixels occlusion state.
void DeviceFilter::initialize(const Pose& pose, const InitialSpread& spread) {
  initialize_modes(std::span<const Pose>(&pose, 1), spread);
}

std::vector<double> DeviceFilter::score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                              const ObservationModel& model) {
  if (!scorer_) scorer_ = std::make_unique<DevicePoseScorer>(*queue_, mesh_, camera_, config_);
  return scorer_->score(poses, depth, model);
}

// Drawn on the device (cl/initialize.cl) with the reference's draws, particle i around mode
// i % modes: no host copy of particles x pixels values at start-up.
void DeviceFilter::initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) {
  if (modes.empty()) throw InputError("initialize_modes: no pose to start from");
  Kernels& k = *kernels_;
  std::vector<float> mode_values;
  mode_values.reserve(modes.size() * 7);
  for (const Pose& m : modes) {
    const Eigen::Quaterniond& q = m.rotation;
    for (double v : {m.translation.x(), m.translation.y(), m.translation.z(), q.w(), q.x(), q.y(), q.z()})
      mode_values.push_back(static_cast<float>(v));
  }
  compute::Buffer<float> mode_buffer(*queue_, mode_values.size());
  mode_buffer.upload(mode_values);
  const InitialArgs args{static_cast<float>(spread.metres), static_cast<float>(spread.radians),
                         static_cast<float>(centre_.x()),   static_cast<float>(centre_.y()),
                         static_cast<float>(centre_.z()),   static_cast<unsigned>(modes.size())};
  const auto linear = compute::NdRange::linear(round_up(count_, kLinearGroup), kLinearGroup);
  compute::set_arg(*k.initialize_particles, 0, state_);
  k.initialize_particles->set_arg(1, static_cast<unsigned>(count_));
  k.initialize_particles->set_arg(2, static_cast<unsigned>(config_.seed & 0xffffffffu));
  k.initialize_particles->set_arg(3, static_cast<unsigned>(config_.seed >> 32));
  compute::set_arg(*k.initialize_particles, 4, mode_buffer);
  k.initialize_particles->set_arg(5, args);
  queue_->launch(*k.initialize_particles, linear);

  compute::set_arg(*k.fill, 0, log_weight_);
  k.fill->set_arg(1, static_cast<unsigned>(count_));
  k.fill->set_arg(2, 0.0f);
  queue_->launch(*k.fill, linear);

  auto fill_pixels = [&](compute::Buffer<float>& values, float value) {
    compute::set_arg(*k.fill_per_particle, 0, values);
    k.fill_per_particle->set_arg(1, static_cast<unsigned>(pixels_));
    k.fill_per_particle->set_arg(2, value);
    queue_->launch(*k.fill_per_particle, compute::NdRange::linear(count_ * kGroupSize, kGroupSize));
  };
  if (config_.occlusion_storage != OcclusionStorage::Off)
    fill_pixels(occlusion_, static_cast<float>(config_.occlusion.initial));
  if (config_.occlusion_storage == OcclusionStorage::PerPixelTime) fill_pixels(occlusion_time_, 0.0f);
  queue_->finish();
  frame_ = 0;
  time_ = 0;
  last_resampled_ = false;
  weighed_in_scratch_ = false;
}

void DeviceFilter::set_state(const std::vector<reference::ParticleState>& particles,
                             const std::vector<float>& occlusion, const std::vector<float>& occlusion_time,
                             const std::vector<double>& log_weights) {
  if (particles.size() != count_ || log_weights.size() != count_)
    throw InputError("set_state: expected " + std::to_string(count_) + " particles");
  upload_particles(particles);
  log_weight_.upload(std::vector<float>(log_weights.begin(), log_weights.end()));
  if (!occlusion.empty()) occlusion_.upload(occlusion);
  if (!occlusion_time.empty()) occlusion_time_.upload(occlusion_time);
}

std::vector<reference::ParticleState> DeviceFilter::unpack(const compute::Buffer<float>& state) const {
  return unpack_particles(state.download());
}

std::vector<reference::ParticleState> DeviceFilter::particles() const {
  return unpack(state_);
}

std::vector<float> DeviceFilter::occlusion_state() const {
  return config_.occlusion_storage == OcclusionStorage::Off ? std::vector<float>{} : occlusion_.download();
}

std::vector<float> DeviceFilter::occlusion_times() const {
  return config_.occlusion_storage == OcclusionStorage::PerPixelTime ? occlusion_time_.download()
                                                                     : std::vector<float>{};
}

// Resampling gathers into the scratch buffer and swaps, so the weighed states are left there.
std::vector<reference::ParticleState> DeviceFilter::weighed_particles() const {
  return unpack(weighed_in_scratch_ ? scratch_state_ : state_);
}

// Timed to the end of the hand-off, so that the per-step split holds for asynchronous paths too.
void DeviceFilter::render_atlas(StepTimings& timings) {
  atlas_source_->draw(state_, atlas_, timings);
  const Stopwatch clock;
  queue_->finish();
  timings.handoff_ms += clock.elapsed_ms();
}

std::vector<float> DeviceFilter::last_atlas() const {
  return atlas_source_->layout().tiles_in_order(atlas_.download(), count_);
}

Estimate DeviceFilter::update(const DepthImage& depth, double dt) {
  const Stopwatch frame_clock;
  Kernels& k = *kernels_;
  Estimate e;
  time_ += dt;
  // Device timings are read once the frame's work is done: asking an event earlier would make the
  // host wait after every kernel.
  compute::EventPtr propagated;
  if (dt > 0) {
    const MotionModel& m = config_.motion;
    const double keep = std::pow(m.damping, dt * m.reference_rate);
    const double spread = std::sqrt((1.0 - keep * keep) / (1.0 - m.damping * m.damping));
    const MotionArgs args{static_cast<float>(keep),
                          static_cast<float>(m.sigma_linear * m.reference_rate * spread),
                          static_cast<float>(m.sigma_angular * m.reference_rate * spread),
                          static_cast<float>(dt),
                          static_cast<float>(centre_.x()),
                          static_cast<float>(centre_.y()),
                          static_cast<float>(centre_.z())};
    compute::set_arg(*k.propagate, 0, state_);
    k.propagate->set_arg(1, static_cast<unsigned>(count_));
    k.propagate->set_arg(2, static_cast<unsigned>(config_.seed & 0xffffffffu));
    k.propagate->set_arg(3, static_cast<unsigned>(config_.seed >> 32));
    k.propagate->set_arg(4, frame_);
    k.propagate->set_arg(5, args);
    propagated = queue_->launch(*k.propagate, compute::NdRange::linear(round_up(count_, kLinearGroup), kLinearGroup));
  }

  render_atlas(e.timings);
  observed_.upload(depth.data());

  const ModelArgs model = model_args(config_);
  compute::set_arg(*k.weigh, 0, atlas_);
  compute::set_arg(*k.weigh, 1, observed_);
  compute::set_arg(*k.weigh, 2, occlusion_);
  compute::set_arg(*k.weigh, 3, occlusion_time_);
  compute::set_arg(*k.weigh, 4, log_likelihood_);
  compute::set_arg(*k.weigh, 5, log_weight_);
  k.weigh->set_arg(6, static_cast<unsigned>(pixels_));
  k.weigh->set_arg(7, model);
  k.weigh->set_arg(8, static_cast<float>(time_));
  k.weigh->set_arg(9, static_cast<float>(dt));
  k.weigh->set_arg(10, atlas_source_->layout().kernel_args());
  // The occlusion priors for the refinement go to the resampling's scratch, free until it gathers.
  compute::set_arg(*k.weigh, 11, scratch_occlusion_);
  k.weigh->set_arg(12, static_cast<unsigned>(config_.refine.enabled));
  const compute::EventPtr weighed = queue_->launch(*k.weigh, compute::NdRange::linear(count_ * kGroupSize, kGroupSize));

  compute::set_arg(*k.summarize, 0, state_);
  compute::set_arg(*k.summarize, 1, log_weight_);
  compute::set_arg(*k.summarize, 2, log_likelihood_);
  compute::set_arg(*k.summarize, 3, weights_);
  compute::set_arg(*k.summarize, 4, estimate_);
  k.summarize->set_arg(5, static_cast<unsigned>(count_));
  k.summarize->set_arg(6, static_cast<float>(centre_.x()));
  k.summarize->set_arg(7, static_cast<float>(centre_.y()));
  k.summarize->set_arg(8, static_cast<float>(centre_.z()));
  const compute::EventPtr summarized = queue_->launch(*k.summarize, compute::NdRange::linear(kGroupSize, kGroupSize));
  const compute::EventPtr refined = config_.refine.enabled ? refine() : nullptr;

  float est[DT_EST_SIZE];
  estimate_.download(std::span<float>(est, DT_EST_SIZE));
  e.pose = Pose({est[DT_EST_TX], est[DT_EST_TX + 1], est[DT_EST_TX + 2]},
                Eigen::Quaterniond(est[DT_EST_QW], est[DT_EST_QW + 1], est[DT_EST_QW + 2], est[DT_EST_QW + 3]));
  e.linear_velocity = Eigen::Vector3d(est[DT_EST_VX], est[DT_EST_VX + 1], est[DT_EST_VX + 2]);
  e.angular_velocity = Eigen::Vector3d(est[DT_EST_WX], est[DT_EST_WX + 1], est[DT_EST_WX + 2]);
  e.effective_sample_size = est[DT_EST_ESS];
  e.max_log_likelihood = est[DT_EST_MAX_LL];
  e.mean_log_likelihood = est[DT_EST_MEAN_LL];
  e.resampled = est[DT_EST_KL] > config_.resample_kl_threshold;
  if (config_.refine.enabled)
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) e.covariance(r, c) = est[DT_EST_COV + 6 * r + c];
  last_resampled_ = e.resampled;
  weighed_in_scratch_ = e.resampled;
  std::vector<compute::EventPtr> resampling;
  if (e.resampled) resampling = resample();
  const compute::EventPtr shifted = config_.refine.enabled ? shift_particles() : nullptr;
  if (propagated) e.timings.propagate_ms = propagated->elapsed_ms();
  e.timings.weigh_ms = weighed->elapsed_ms();
  e.timings.resample_ms = summarized->elapsed_ms();
  for (const auto& event : resampling) e.timings.resample_ms += event->elapsed_ms();
  if (refined) e.timings.refine_ms = refined->elapsed_ms() + shifted->elapsed_ms();
  e.timings.total_ms = frame_clock.elapsed_ms();
  ++frame_;
  return e;
}

std::vector<compute::EventPtr> DeviceFilter::resample() {
  Kernels& k = *kernels_;
  const dt_philox4 words = dt_random_words(config_.seed, 0u, frame_, DT_STREAM_RESAMPLE, 0u);
  const auto linear = compute::NdRange::linear(round_up(count_, kLinearGroup), kLinearGroup);
  const auto per_particle_group = compute::NdRange::linear(count_ * kGroupSize, kGroupSize);
  const unsigned count = static_cast<unsigned>(count_);
  std::vector<compute::EventPtr> events;

  compute::set_arg(*k.prefix_sum, 0, weights_);
  compute::set_arg(*k.prefix_sum, 1, cumulative_);
  k.prefix_sum->set_arg(2, count);
  events.push_back(queue_->launch(*k.prefix_sum, compute::NdRange::linear(kGroupSize, kGroupSize)));

  compute::set_arg(*k.find_parents, 0, cumulative_);
  compute::set_arg(*k.find_parents, 1, parents_);
  k.find_parents->set_arg(2, count);
  k.find_parents->set_arg(3, dt_uniform01(words.v[0]));
  events.push_back(queue_->launch(*k.find_parents, linear));

  compute::set_arg(*k.gather_state, 0, state_);
  compute::set_arg(*k.gather_state, 1, scratch_state_);
  compute::set_arg(*k.gather_state, 2, parents_);
  k.gather_state->set_arg(3, count);
  events.push_back(queue_->launch(*k.gather_state, linear));
  std::swap(state_, scratch_state_);

  auto gather_pixels = [&](compute::Buffer<float>& state, compute::Buffer<float>& scratch) {
    compute::set_arg(*k.gather_pixels, 0, state);
    compute::set_arg(*k.gather_pixels, 1, scratch);
    compute::set_arg(*k.gather_pixels, 2, parents_);
    k.gather_pixels->set_arg(3, static_cast<unsigned>(pixels_));
    events.push_back(queue_->launch(*k.gather_pixels, per_particle_group));
    std::swap(state, scratch);
  };
  if (config_.occlusion_storage != OcclusionStorage::Off) gather_pixels(occlusion_, scratch_occlusion_);
  if (config_.occlusion_storage == OcclusionStorage::PerPixelTime)
    gather_pixels(occlusion_time_, scratch_occlusion_time_);

  compute::set_arg(*k.fill, 0, log_weight_);
  k.fill->set_arg(1, count);
  k.fill->set_arg(2, 0.0f);
  events.push_back(queue_->launch(*k.fill, linear));
  return events;
}

compute::EventPtr DeviceFilter::refine() {
  Kernels& k = *kernels_;
  const Refinement& r = config_.refine;
  const RefineArgs args{static_cast<float>(r.damping),
                        static_cast<float>(r.min_incidence),
                        static_cast<float>(centre_.x()),
                        static_cast<float>(centre_.y()),
                        static_cast<float>(centre_.z()),
                        static_cast<float>(time_),
                        r.iterations};
  compute::set_arg(*k.refine, 0, estimate_);
  compute::set_arg(*k.refine, 1, state_);
  compute::set_arg(*k.refine, 2, observed_);
  compute::set_arg(*k.refine, 3, occlusion_);
  compute::set_arg(*k.refine, 4, occlusion_time_);
  compute::set_arg(*k.refine, 5, scratch_occlusion_);  // weigh's priors
  compute::set_arg(*k.refine, 6, atlas_);
  k.refine->set_arg(7, atlas_source_->layout().kernel_args());
  compute::set_arg(*k.refine, 8, refine_mesh_->vertices);
  compute::set_arg(*k.refine, 9, refine_mesh_->triangles);
  compute::set_arg(*k.refine, 10, refine_mesh_->planes);
  k.refine->set_arg(11, refine_mesh_->triangle_count());
  k.refine->set_arg(12, raster_camera_args(camera_, config_));
  k.refine->set_arg(13, model_args(config_));
  k.refine->set_arg(14, args);
  compute::set_arg(*k.refine, 15, refine_pose_);
  compute::set_arg(*k.refine, 16, refine_tile_);
  compute::set_arg(*k.refine, 17, refine_ids_);
  compute::set_arg(*k.refine, 18, correction_);
  return queue_->launch(*k.refine, compute::NdRange::linear(kGroupSize, kGroupSize));
}

compute::EventPtr DeviceFilter::shift_particles() {
  Kernels& k = *kernels_;
  // After resampling the weighed states are in the scratch buffer already: shift in place.
  compute::set_arg(*k.shift_particles, 0, state_);
  compute::set_arg(*k.shift_particles, 1, weighed_in_scratch_ ? state_ : scratch_state_);
  k.shift_particles->set_arg(2, static_cast<unsigned>(count_));
  compute::set_arg(*k.shift_particles, 3, correction_);
  k.shift_particles->set_arg(4, static_cast<float>(centre_.x()));
  k.shift_particles->set_arg(5, static_cast<float>(centre_.y()));
  k.shift_particles->set_arg(6, static_cast<float>(centre_.z()));
  const compute::EventPtr event =
      queue_->launch(*k.shift_particles, compute::NdRange::linear(round_up(count_, kLinearGroup), kLinearGroup));
  if (!weighed_in_scratch_) std::swap(state_, scratch_state_);
  weighed_in_scratch_ = true;
  return event;
}

std::vector<double> DeviceFilter::last_log_likelihoods() const {
  const std::vector<float> ll = log_likelihood_.download();
  return std::vector<double>(ll.begin(), ll.end());
}

std::vector<int> DeviceFilter::last_parents() const {
  std::vector<int> parents(count_);
  if (!last_resampled_) {
    std::iota(parents.begin(), parents.end(), 0);
    return parents;
  }
  const std::vector<unsigned> p = parents_.download();
  for (size_t i = 0; i < count_; ++i) parents[i] = static_cast<int>(p[i]);
  return parents;
}

}  // namespace depthtrack
