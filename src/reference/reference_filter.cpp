#include "reference/reference_filter.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <depthtrack/error.hpp>
#include <limits>
#include <numeric>
#include <sstream>

#include "core/stopwatch.hpp"
#include "model/occlusion_chain.hpp"
#include "philox.h"
#include "reference/observation_model.hpp"
#include "reference/pose_mean.hpp"
#include "reference/pose_score.hpp"
#include "reference/weights.hpp"

namespace depthtrack::reference {

namespace {

// Host memory for `state_pixels` of occlusion state a particle: occlusion probabilities and times, each
// with a resampling twin, plus the particle, its twin, and the per-particle weights and likelihoods.
struct HostMemory {
  double available = 0, fixed_per_particle = 0, per_state_pixel = 0;

  explicit HostMemory(const TrackerConfig& config) {
    const bool occlusion = config.occlusion_storage != OcclusionStorage::Off;
    const bool times = config.occlusion_storage == OcclusionStorage::PerPixelTime;
    available = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
    per_state_pixel = 4.0 * ((occlusion ? 2 : 0) + (times ? 2 : 0));
    fixed_per_particle = 2.0 * sizeof(ParticleState) + 6 * sizeof(double) + sizeof(int) + sizeof(Pose);
  }
  double per_particle(size_t state_pixels) const {
    return per_state_pixel * static_cast<double>(state_pixels) + fixed_per_particle;
  }
  // The most state pixels a particle can have in 80 % of the memory (0: unknown, no bound).
  size_t state_pixel_limit(int particles) const {
    if (!(available > 0) || per_state_pixel == 0) return 0;
    const double share = 0.8 * available / particles - fixed_per_particle;
    return share < 1 ? 1 : static_cast<size_t>(share / per_state_pixel);
  }
};

// Checked before allocating, like the device filter's memory check: 2e9 particles used to end in
// std::bad_alloc, or in the system's out-of-memory killer. An automatic state window is checked again
// at the start, once it is sized.
void check_host_memory(const TrackerConfig& config, const Camera& camera, const model::StateWindow& window) {
  const HostMemory memory(config);
  const double per_particle = memory.per_particle(window.pixels());
  const double needed = per_particle * config.particles;
  if (memory.available > 0 && needed > 0.8 * memory.available) {
    std::ostringstream m;
    m.precision(3);
    m << model::particles_and_window(config, camera, window) << " need " << needed / (1 << 30)
      << " GiB of memory for the reference filter but this machine has " << memory.available / (1 << 30)
      << " GiB; at most about " << static_cast<long long>(0.8 * memory.available / per_particle) << " particles fit";
    throw InputError(m.str());
  }
}

// model::propagate_occlusion with pow(c, dt) kept for the last dt: a particle's pixels were last seen at
// a few times, most at the last frame's, so most pixels skip the pow. The same value, bit for bit.
class OcclusionAger {
 public:
  explicit OcclusionAger(const OcclusionModel& m)
      : c_(m.p_occluded_stays - m.p_visible_to_occluded), p_inf_(model::occlusion_steady_state(m)) {}
  double operator()(double p, double dt) {
    if (!(dt == last_dt_)) {
      last_dt_ = dt;
      factor_ = std::pow(c_, dt);
    }
    return p_inf_ + factor_ * (p - p_inf_);
  }

 private:
  double c_, p_inf_;
  double last_dt_ = std::numeric_limits<double>::quiet_NaN(), factor_ = 0;
};

}  // namespace

ReferenceFilter::ReferenceFilter(const Mesh& mesh, const Camera& camera, const TrackerConfig& config, int threads)
    : config_(config),
      camera_(camera),
      centre_(mesh.centre().cast<double>()),
      refiner_(mesh, camera, config),
      scorer_(mesh, camera, config),
      extent_(model::object_extent(mesh)),
      window_(model::state_window_size(config, camera)),
      next_window_(window_),
      state_pixel_limit_(HostMemory(config).state_pixel_limit(config.particles)) {
  check_host_memory(config, camera, window_);
  const size_t n = static_cast<size_t>(config.particles), pixels = static_cast<size_t>(camera.pixel_count());
  pool_ = std::make_unique<ThreadPool>(threads);
  for (int t = 0; t < threads; ++t)
    lanes_.push_back(Lane{
        Rasterizer(mesh, camera, config.near_plane, config.observation.max_depth), std::vector<float>(pixels), {}, {}});
  particles_.resize(n);
  log_weights_.assign(n, 0.0);  // the occlusion rows are allocated at the start (initialize_modes)
}

std::string ReferenceFilter::description() const {
  if (lanes_.size() == 1) return "reference (sequential CPU)";
  return "cpu (the reference filter on " + std::to_string(lanes_.size()) + " threads)";
}

template <typename F>
void ReferenceFilter::for_chunks(size_t n, F&& f) {
  run_ranges(*pool_, n, [&](size_t c, size_t first, size_t last, int thread) {
    f(lanes_[static_cast<size_t>(thread)], c, first, last);
  });
}

void ReferenceFilter::initialize(const Pose& pose, const InitialSpread& spread) {
  initialize_modes(std::span<const Pose>(&pose, 1), spread);
}

void ReferenceFilter::initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) {
  for (size_t i = 0; i < particles_.size(); ++i)
    particles_[i] = model::draw_initial_particle(config_.seed, i, modes, spread, centre_);
  std::fill(log_weights_.begin(), log_weights_.end(), 0.0);
  window_ = next_window_ = model::start_state_window(config_, extent_, modes.front(), camera_);
  check_host_memory(config_, camera_, window_);  // an automatic window's size is known now
  const size_t kept = particles_.size() * window_.pixels();
  if (config_.occlusion_storage != OcclusionStorage::Off)
    occlusion_.assign(kept, static_cast<float>(config_.occlusion.initial));
  if (config_.occlusion_storage == OcclusionStorage::PerPixelTime) occlusion_time_.assign(kept, 0.0f);
  // The resampling twins sized and touched now, not by the first frame's gather (its page faults took
  // most of a budgeted first frame).
  scratch_occlusion_.assign(occlusion_.size(), 0.0f);
  scratch_occlusion_time_.assign(occlusion_time_.size(), 0.0f);
  scratch_particles_.resize(particles_.size());
  frame_ = 0;
  time_ = 0;
}

std::vector<double> ReferenceFilter::score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                                 const ObservationModel& model) {
  return scorer_.score(poses, depth, model);
}

std::unique_ptr<PoseScorer> ReferenceFilter::make_pose_scorer(const Mesh& mesh) {
  return std::make_unique<ReferencePoseScorer>(mesh, camera_, config_);
}

void ReferenceFilter::propagate(double dt) {
  const model::MotionStep step = model::motion_step(config_.motion, dt);
  for_chunks(particles_.size(), [&](Lane&, size_t, size_t first, size_t last) {
    for (size_t i = first; i < last; ++i) {
      float normals[6];
      dt_normals6(config_.seed, static_cast<dt_u32>(i), frame_, DT_STREAM_MOTION, normals);
      model::propagate_particle(particles_[i], step, centre_, normals);
    }
  });
}

double ReferenceFilter::fresh_occlusion_now() const {
  return config_.occlusion_storage == OcclusionStorage::Off
             ? 0.0
             : model::propagate_occlusion(config_.occlusion, config_.occlusion.initial, time_);
}

double ReferenceFilter::weigh_particle(size_t i, const DepthImage& depth, double dt, Lane& lane, double& magnitude) {
  const Stopwatch render_clock;
  const PixelBox box = lane.rasterizer.render(particles_[i].pose, lane.rendered);
  lane.render_ms += render_clock.elapsed_ms();

  const size_t row = window_.pixels();
  float* occlusion = occlusion_.empty() ? nullptr : occlusion_.data() + i * row;
  float* occlusion_time = occlusion_time_.empty() ? nullptr : occlusion_time_.data() + i * row;
  if (config_.occlusion_storage == OcclusionStorage::GlobalTime && dt > 0)
    for (size_t k = 0; k < row; ++k)
      occlusion[k] = static_cast<float>(model::propagate_occlusion(config_.occlusion, occlusion[k], dt));
  const double fresh = fresh_occlusion_now();  // pixels outside the state window

  double log_likelihood = 0;
  magnitude = 0;
  lane.weighing.clear();
  OcclusionAger age(config_.occlusion);
  for (int v = box.v0; v < box.v1; ++v) {
    for (int u = box.u0; u < box.u1; ++u) {
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(camera_.width) + static_cast<size_t>(u);
      const double y_hat = lane.rendered[k], y = depth.data()[k];
      if (y_hat <= 0 || !DepthImage::is_valid(static_cast<float>(y))) continue;  // adds 0
      const bool kept = window_.contains(u, v);
      const size_t j = kept ? window_.index(u, v) : 0;
      double p = 0;
      if (!kept)
        p = fresh;
      else if (config_.occlusion_storage == OcclusionStorage::PerPixelTime)
        p = age(occlusion[j], time_ - occlusion_time[j]);
      else if (config_.occlusion_storage == OcclusionStorage::GlobalTime)
        p = occlusion[j];
      const PixelDensities d = kept ? pixel_densities(config_.observation, observed_[j], y_hat)
                                    : pixel_densities(config_.observation, y, y_hat);
      const double term = pixel_log_ratio(d, p);
      if (config_.refine.enabled) lane.weighing.push_back({k, p});
      log_likelihood += term;
      magnitude += std::abs(term);
      if (!kept) continue;
      if (occlusion) occlusion[j] = static_cast<float>(occlusion_posterior(d, p));
      if (occlusion_time) occlusion_time[j] = static_cast<float>(time_);
    }
  }
  return log_likelihood;
}

// Before time_ moves on: a pixel new to the window holds what a fresh pixel holds at the last frame's
// time (global time ages it by dt with the rest; per-pixel time keeps its time 0).
void ReferenceFilter::move_state_window() {
  if (next_window_ == window_ || occlusion_.empty()) {
    window_ = next_window_;
    return;
  }
  const model::StateWindow from = window_, to = next_window_;
  const float fresh_p =
      static_cast<float>(config_.occlusion_storage == OcclusionStorage::GlobalTime
                             ? model::propagate_occlusion(config_.occlusion, config_.occlusion.initial, time_)
                             : config_.occlusion.initial);
  auto move = [&](std::vector<float>& rows, std::vector<float>& scratch, float fresh) {
    if (rows.empty()) return;
    scratch.resize(particles_.size() * to.pixels());  // an automatic window grows
    // Each row of the new window: the old window's part of it copied, the rest fresh.
    const int kept_u0 = std::max(from.u0, to.u0), kept_u1 = std::min(from.u0 + from.width, to.u0 + to.width);
    for_chunks(particles_.size(), [&](Lane&, size_t, size_t first, size_t last) {
      for (size_t i = first; i < last; ++i)
        for (int v = to.v0; v < to.v0 + to.height; ++v) {
          float* out = scratch.data() + i * to.pixels() + to.index(to.u0, v);
          if (kept_u0 >= kept_u1 || v < from.v0 || v >= from.v0 + from.height) {
            std::fill_n(out, to.width, fresh);
            continue;
          }
          const float* in = rows.data() + i * from.pixels() + from.index(kept_u0, v);
          std::fill_n(out, kept_u0 - to.u0, fresh);
          std::copy_n(in, kept_u1 - kept_u0, out + (kept_u0 - to.u0));
          std::fill(out + (kept_u1 - to.u0), out + to.width, fresh);
        }
    });
    rows.swap(scratch);
  };
  move(occlusion_, scratch_occlusion_, fresh_p);
  move(occlusion_time_, scratch_occlusion_time_, 0.0f);
  window_ = next_window_;
}

void ReferenceFilter::resample(const std::vector<double>& normalized) {
  const dt_philox4 words = dt_random_words(config_.seed, 0u, frame_, DT_STREAM_RESAMPLE, 0u);
  last_parents_ = systematic_resample(normalized, dt_uniform01(words.v[0]));
  gather(last_parents_);
}

void ReferenceFilter::gather(const std::vector<int>& parents) {
  const size_t pixels = window_.pixels(), children = parents.size();
  // Children are gathered into the scratch copies, which then become the state (one copy; no allocation
  // while the count stays).
  auto gather_rows = [&](std::vector<float>& state, std::vector<float>& scratch) {
    if (state.empty()) return;
    scratch.resize(children * pixels);
    for_chunks(children, [&](Lane&, size_t, size_t first, size_t last) {
      for (size_t child = first; child < last; ++child)
        std::copy_n(state.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(parents[child]) * pixels), pixels,
                    scratch.begin() + static_cast<std::ptrdiff_t>(child * pixels));
    });
    state.swap(scratch);
  };
  gather_rows(occlusion_, scratch_occlusion_);
  gather_rows(occlusion_time_, scratch_occlusion_time_);
  scratch_particles_.resize(children);
  // A copy of about 100 bytes a particle: on one thread, as handing it to the pool would cost more.
  for (size_t child = 0; child < children; ++child)
    scratch_particles_[child] = particles_[static_cast<size_t>(parents[child])];
  particles_.swap(scratch_particles_);
  log_weights_.assign(children, 0.0);
}

void ReferenceFilter::set_particle_count(int count) {
  if (count < 1 || count > config_.particles)
    throw InputError("particle count " + std::to_string(count) +
                     " must be in [1, particles = " + std::to_string(config_.particles) + "]");
  if (static_cast<size_t>(count) == particles_.size()) return;
  // The weights the next resampling would draw from; frame_ is the next update's, so the words differ
  // from any resampling's.
  const WeightSummary weights = summarize_log_weights(log_weights_);
  const dt_philox4 words = dt_random_words(config_.seed, 0u, frame_, DT_STREAM_RESIZE, 0u);
  gather(systematic_resample(weights.normalized, dt_uniform01(words.v[0]), static_cast<size_t>(count)));
}

// The prior, not the posterior: the posterior already holds this frame's evidence as seen from the
// heaviest particle's pose, and would mark pixels where that pose is off as occluded, dropping the
// very residuals that correct it (measured: ycbv-0000 mug, mean rotation error 4.2 -> 2.1 degrees).
std::vector<double> ReferenceFilter::occlusion_map(size_t i) const {
  if (config_.occlusion_storage == OcclusionStorage::Off) return {};
  std::vector<double> p(static_cast<size_t>(camera_.pixel_count()), fresh_occlusion_now());
  const size_t row = window_.pixels();
  OcclusionAger age(config_.occlusion);
  for (int v = window_.v0; v < window_.v0 + window_.height; ++v)
    for (int u = window_.u0; u < window_.u0 + window_.width; ++u) {
      const size_t j = i * row + window_.index(u, v);
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(camera_.width) + static_cast<size_t>(u);
      p[k] = occlusion_[j];
      if (config_.occlusion_storage == OcclusionStorage::PerPixelTime) p[k] = age(p[k], time_ - occlusion_time_[j]);
    }
  for (const PixelPrior& prior : priors_) p[prior.pixel] = prior.p;  // the pixels its update changed
  return p;
}

// From the heaviest particle, not the weighted mean: their float and double versions differ by up to
// 1e-5 m when two particles share the weight, and a fit from different starts ends apart in the weakly
// observed directions; the heaviest particle is the same on every backend.
void ReferenceFilter::refine(Estimate& e, const DepthImage& depth, size_t heaviest) {
  last_fit_occlusion_ = occlusion_map(heaviest);
  const RefinedPose fit = refiner_.refine(particles_[heaviest].pose, depth, last_fit_occlusion_);
  // The cloud moves by the twist that puts the heaviest particle on the refined pose: the refined
  // pose enters the particle set exactly.
  const Vector6d correction = twist_between(particles_[heaviest].pose, fit.pose, centre_);
  for_chunks(particles_.size(), [&](Lane&, size_t, size_t first, size_t last) {
    for (size_t i = first; i < last; ++i) particles_[i].pose = apply_twist(particles_[i].pose, centre_, correction);
  });
  e.pose = fit.pose;
  e.covariance = fit.covariance;
  e.refine_iterations = fit.iterations;
  e.confidence = fit.visible_share;
}

size_t ReferenceFilter::weigh_all(const DepthImage& depth, double dt, Estimate& e) {
  const Stopwatch weigh_clock;
  last_log_likelihoods_.resize(particles_.size());
  last_magnitudes_.resize(particles_.size());
  for (Lane& lane : lanes_) lane.render_ms = 0;
  // The state window's valid pixels' observed-depth terms, for every particle (weigh_particle).
  observed_.resize(window_.pixels());
  for_chunks(static_cast<size_t>(window_.height), [&](Lane&, size_t, size_t first, size_t last) {
    for (size_t row = first; row < last; ++row) {
      const int v = window_.v0 + static_cast<int>(row);
      for (int u = window_.u0; u < window_.u0 + window_.width; ++u) {
        const float y = depth.at(u, v);
        if (DepthImage::is_valid(y)) observed_[window_.index(u, v)] = observed_depth(config_.observation, y);
      }
    }
  });
  chunk_heaviest_.resize(range_count(*pool_, particles_.size()));
  for_chunks(particles_.size(), [&](Lane& lane, size_t c, size_t first, size_t last) {
    ChunkHeaviest& mine = chunk_heaviest_[c];
    mine.found = false;
    for (size_t i = first; i < last; ++i) {
      last_log_likelihoods_[i] = weigh_particle(i, depth, dt, lane, last_magnitudes_[i]);
      log_weights_[i] += last_log_likelihoods_[i];
      // The first of equal maxima, as max_element; particle 0 is taken whatever its weight (a NaN
      // there stays the heaviest, as in one sequential scan).
      const double so_far = mine.found ? mine.log_weight : -std::numeric_limits<double>::infinity();
      if (i == 0 || log_weights_[i] > so_far) {
        mine.found = true;
        mine.log_weight = log_weights_[i];
        mine.index = i;
        mine.priors.swap(lane.weighing);
      }
    }
  });
  // The chunks' heaviest in chunk order, a later one only when strictly heavier: the sequential result.
  ChunkHeaviest* heaviest = nullptr;
  for (ChunkHeaviest& c : chunk_heaviest_)
    if (c.found && (!heaviest || c.log_weight > heaviest->log_weight)) heaviest = &c;
  double render_ms = 0;
  for (const Lane& lane : lanes_) render_ms += lane.render_ms;
  // Render time summed over threads, per thread: the wall-clock share of the render in the weigh step.
  e.timings.render_ms = render_ms / static_cast<double>(lanes_.size());
  e.timings.weigh_ms = weigh_clock.elapsed_ms() - e.timings.render_ms;
  if (!heaviest) return 0;  // no particle
  priors_.swap(heaviest->priors);
  return heaviest->index;
}

Estimate ReferenceFilter::update(const DepthImage& depth, double dt) {
  const Stopwatch frame_clock;
  Estimate e;
  move_state_window();
  time_ += dt;
  if (dt > 0) {
    const Stopwatch clock;
    propagate(dt);
    e.timings.propagate_ms = clock.elapsed_ms();
  }

  const size_t heaviest = weigh_all(depth, dt, e);

  const Stopwatch resample_clock;
  const WeightSummary weights = summarize_log_weights(log_weights_);
  last_normalized_ = weights.normalized;
  std::vector<Pose> poses(particles_.size());
  Eigen::Vector3d linear = Eigen::Vector3d::Zero(), angular = Eigen::Vector3d::Zero();
  double mean_log_likelihood = 0;
  for (size_t i = 0; i < particles_.size(); ++i) {
    poses[i] = particles_[i].pose;
    linear += weights.normalized[i] * particles_[i].linear_velocity;
    angular += weights.normalized[i] * particles_[i].angular_velocity;
    mean_log_likelihood += weights.normalized[i] * last_log_likelihoods_[i];
  }
  e.pose = weighted_mean_pose(poses, weights.normalized, centre_, pool_.get());
  e.linear_velocity = linear;
  e.angular_velocity = angular;
  e.effective_sample_size = weights.effective_sample_size;
  e.max_log_likelihood = *std::max_element(last_log_likelihoods_.begin(), last_log_likelihoods_.end());
  e.mean_log_likelihood = mean_log_likelihood;
  e.resampled = weights.kl_from_uniform > config_.resample_kl_threshold;
  e.timings.resample_ms = resample_clock.elapsed_ms();
  if (config_.refine.enabled) {
    const Stopwatch refine_clock;
    refine(e, depth, heaviest);
    e.timings.refine_ms = refine_clock.elapsed_ms();
  }
  const Stopwatch gather_clock;
  if (e.resampled) {
    resample(weights.normalized);
  } else {
    last_parents_.resize(particles_.size());
    std::iota(last_parents_.begin(), last_parents_.end(), 0);
  }
  e.timings.resample_ms += gather_clock.elapsed_ms();
  next_window_ = model::next_state_window(window_, config_, extent_, e.pose, camera_, state_pixel_limit_);
  e.timings.total_ms = frame_clock.elapsed_ms();
  ++frame_;
  return e;
}

}  // namespace depthtrack::reference
