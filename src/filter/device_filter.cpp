#include "filter/device_filter.hpp"

#include <depthtrack/error.hpp>

#include "core/stopwatch.hpp"
#include "dt_state.h"
#include "dt_summary.h"
#include "filter/device_pose_scorer.hpp"
#include "filter/device_refiner.hpp"
#include "model/fit_noise.hpp"
#include "model/kernel_params.hpp"
#include "philox.h"
#include "reference/weights.hpp"

namespace depthtrack {

namespace {
// A run of launches' device time from its first event to its last, the gaps between them included
// (the launches between are untimed); the events' own times added where the backend has no common clock.
double device_span_ms(const std::vector<compute::EventPtr>& events) {
  if (events.size() > 1)
    if (const auto span = events.back()->elapsed_since_ms(*events.front())) return *span;
  double ms = 0;
  for (const auto& event : events) ms += event->elapsed_ms();
  return ms;
}

}  // namespace

struct DeviceFilter::Pending {
  Stopwatch clock;
  FrameEvents events;
};

DeviceFilter::DeviceFilter(std::unique_ptr<compute::Queue> queue, const Mesh& mesh, const Camera& camera,
                           const TrackerConfig& config)
    : DeviceFilter(std::make_shared<compute::DeviceContext>(std::move(queue)), mesh, camera, config) {}

DeviceFilter::DeviceFilter(std::shared_ptr<compute::DeviceContext> device, const Mesh& mesh, const Camera& camera,
                           const TrackerConfig& config, const GlAtlasDevice* gl)
    : device_(std::move(device)),
      own_queue_(device_->make_queue()),
      queue_(own_queue_ ? own_queue_.get() : device_->queue.get()),
      config_(config),
      camera_(camera),
      centre_(mesh.centre().cast<double>()),
      mesh_(mesh),
      sizes_(frame_sizes(mesh, camera, config)),
      plan_(make_frame_plan(config, queue_->info(), sizes_)),
      layouts_(frame_plan_layouts(config, queue_->info(), sizes_)),
      extent_(model::object_extent(mesh)),
      window_(model::state_window_size(config, camera)),
      next_window_(window_),
      rows_(*queue_, config_, camera, plan_, window_),
      atlas_source_(make_atlas_source(*queue_, device_->programs, mesh, camera, config, gl)),
      buffers_(*queue_, plan_, atlas_source_->layout().floats(), config.refine.enabled) {
  // An automatic window's rows are allocated once the start sizes it.
  rows_.reserve_current(window_);
  rows_.reserve_scratch(window_);
  frame_times_ = std::make_unique<FrameTimeTable>(*queue_);
  if (plan_.refine) {  // the fit in the plan's layout
    TrackerConfig fit = config;
    fit.refine.layout = *plan_.refine;
    refiner_ = std::make_unique<DeviceRefiner>(*queue_, device_->programs, mesh, camera, fit,
                                               model::occlusion_definition(config.occlusion_storage));
  }
  steps_ = std::make_unique<FrameSteps>(*queue_, device_->programs, plan_, layouts_, config_, camera_, *atlas_source_,
                                        buffers_, rows_, *frame_times_);
}

DeviceFilter::~DeviceFilter() {
  // A shared queue may outlive this filter: a read of an uncollected (or failed) frame's estimate
  // lands before the estimate's host copy goes.
  try {
    queue_->wait_enqueued_reads();
  } catch (...) {  // a device error at teardown has nowhere to go
  }
}

std::string DeviceFilter::description() const {
  const auto& info = queue_->info();
  return info.selector + " " + info.name + " (" + info.platform + "); atlas: " + atlas_source_->description() +
         (plan_.weigh == WeighStep::RenderWeigh ? "; drawn inside weigh (tiles in work-group memory)" : "");
}

std::vector<double> DeviceFilter::score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                              const ObservationModel& model) {
  if (!scorer_) scorer_ = make_pose_scorer(mesh_);
  return scorer_->score(poses, depth, model);
}

std::unique_ptr<PoseScorer> DeviceFilter::make_pose_scorer(const Mesh& mesh) {
  if (!scoring_programs_) scoring_programs_ = std::make_shared<const DevicePoseScorerPrograms>(device_->programs);
  return std::make_unique<DevicePoseScorer>(*queue_, scoring_programs_, mesh, camera_, config_);
}

void DeviceFilter::initialize(const Pose& pose, const InitialSpread& spread) {
  initialize_modes(std::span<const Pose>(&pose, 1), spread);
}

// Drawn on the device (cl/initialize.cl) with the reference's draws, particle i around mode
// i % modes: start-up holds no host copy of the particles or of their particles x pixels occlusion state.
void DeviceFilter::initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) {
  if (modes.empty()) throw InputError("initialize_modes: no pose to start from");
  std::vector<float> mode_values;
  mode_values.reserve(modes.size() * 7);
  for (const Pose& m : modes) {
    const Eigen::Quaterniond& q = m.rotation;
    for (double v : {m.translation.x(), m.translation.y(), m.translation.z(), q.w(), q.x(), q.y(), q.z()})
      mode_values.push_back(static_cast<float>(v));
  }
  // An automatic window is sized here: its rows are checked and allocated (a fixed one's already were).
  window_ = next_window_ = model::start_state_window(config_, extent_, modes.front(), camera_);
  rows_.check(window_);
  rows_.reserve_current(window_);
  steps_->initialize(mode_values, model::initial_params(spread, centre_, modes.size()), window_.pixels());
  rows_particles_ = plan_.particles;
  frame_ = 0;
  time_ = 0;
  last_resampled_ = false;
  weighed_in_scratch_ = false;
}

void DeviceFilter::set_particle_count(int count) {
  if (count < 1 || count > config_.particles)
    throw InputError("particle count " + std::to_string(count) +
                     " must be in [1, particles = " + std::to_string(config_.particles) + "]");
  if (pending_) throw InputError("device filter: set_particle_count() while a frame is not collected");
  const size_t from = plan_.particles, to = static_cast<size_t>(count);
  if (to == from) return;
  // The reads wait for the last frame's resampling; the log weights are 0 after a resampling, as the
  // reference's.
  std::vector<float> log_weight(from);
  std::vector<unsigned> parents(from);
  buffers_.log_weight.download(std::span<float>(log_weight));
  buffers_.parents.download(std::span<unsigned>(parents));
  const reference::WeightSummary weights =
      reference::summarize_log_weights(std::vector<double>(log_weight.begin(), log_weight.end()));
  const dt_philox4 words = dt_random_words(config_.seed, 0u, frame_, DT_STREAM_RESIZE, 0u);
  const std::vector<int> drawn = reference::systematic_resample(weights.normalized, dt_uniform01(words.v[0]), to);
  // Child j is particle drawn[j]: its kinematic state, and the occlusion rows that particle reads next.
  std::vector<unsigned> choice(to), rows(to);
  for (size_t j = 0; j < to; ++j) {
    choice[j] = static_cast<unsigned>(drawn[j]);
    rows[j] = parents[choice[j]];
  }
  plan_ = make_frame_plan(config_, queue_->info(), sizes_, to);
  buffers_.choice.upload(std::span<const unsigned>(choice));
  buffers_.parents.upload(std::span<const unsigned>(rows));
  steps_->gather(buffers_.choice, to);
  weighed_in_scratch_ = false;  // the weighed states were the last count's
}

// One enqueue sequence per frame and one wait, the estimate's read in collect(): the depth goes up
// first (a blocking write waits for the work enqueued before it on this queue), the resampling decision
// is made on the device (summarize.cl's flag, read by the resampling kernels), and the device times are
// read from the events once the frame is done.
Estimate DeviceFilter::update(const DepthImage& depth, double dt) {
  enqueue_update(depth, dt);
  return collect();
}

void DeviceFilter::enqueue_update(const DepthImage& depth, double dt) {
  if (pending_) throw InputError("device filter: enqueue_update() while the previous frame is not collected");
  auto p = std::make_unique<Pending>();
  FrameEvents& events = p->events;
  // This frame's weigh writes its rows at next_window_ (an automatic window may have grown).
  rows_.reserve_scratch(next_window_);
  time_ += dt;
  const Stopwatch upload;
  buffers_.observed.upload_enqueued(depth.data());  // the frame's launches follow it in order
  events.timings.upload_ms = upload.elapsed_ms();
  // The frame's launches as one batch (a CUDA graph, replayed frame after frame). Only where every
  // launch goes through the queue: the GL renderer's hand-off enqueues work of its own.
  compute::LaunchBatch batch(*queue_, atlas_source_->device_mesh() != nullptr);
  FrameInputs in;
  in.now = static_cast<float>(time_);
  in.dt = static_cast<float>(dt);
  in.frame = frame_;
  in.moves = dt > 0;
  in.motion = dt > 0 ? model::motion_params(model::motion_step(config_.motion, dt), centre_) : dt_motion{};
  steps_->propagate(in, events);
  if (config_.occlusion_storage == OcclusionStorage::PerPixelTime) {
    in.now_index = frame_times_->begin_frame(in.now);
    if (frame_times_->retire_due()) {
      steps_->retire_time_indices(rows_particles_, window_.pixels(), in.now_index);
      frame_times_->retired();
    }
  }
  // Each particle's state from its parent's row into its own row of the other buffers, which then
  // become the state; the rows before stay for the fit's prior. The rows move with the state window
  // (centred on the last estimate).
  in.window = model::window_params(next_window_, window_, camera_, config_);
  window_ = next_window_;
  steps_->weigh(in, keep_atlas_, events);
  rows_particles_ = plan_.particles;
  // The device starts on propagate and weigh (most of a small frame's first half) while the host
  // records the summary, and the summary while it records the fit (on a slow host the device had
  // waited for the fit's 19 launches to be recorded). The estimate's read hands over the fit, the
  // batch's end the resampling.
  batch.flush();
  rows_.swap();
  const float kl_threshold = model::float_threshold(config_.resample_kl_threshold);
  const Eigen::Vector3f centre = centre_.cast<float>();
  // The fit replaces the weighted mean's pose (it starts from the heaviest particle), so its rotation
  // mean is not iterated: 4 of the single group's 7 reductions, or 4 launches of the wide summary.
  const unsigned karcher_steps = refiner_ ? 0u : static_cast<unsigned>(DT_KARCHER_STEPS);
  steps_->summarize(centre, kl_threshold, karcher_steps, events);
  if (plan_.summary != SummaryStep::InsideFit) batch.flush();
  // Before the resampling overwrites parents with this frame's choice.
  if (refiner_) {
    const RefineInputs inputs{.states = buffers_.state,
                              .observed = buffers_.observed,
                              .occlusion = rows_.scratch_occlusion,
                              .occlusion_time = rows_.scratch_time,
                              .frame_times = frame_times_->device(),
                              .parents = buffers_.parents,
                              .window = in.window,
                              .time = time_,
                              .dt = dt};
    const SummaryInputs summary{.log_weight = buffers_.log_weight,
                                .log_likelihood = buffers_.log_likelihood,
                                .weights = buffers_.weights,
                                .count = static_cast<unsigned>(plan_.particles),
                                .centre = centre,
                                .kl_threshold = kl_threshold};
    events.refined =
        refiner_->refine(buffers_.estimate, inputs, plan_.summary == SummaryStep::InsideFit ? &summary : nullptr);
  }
  // The estimate is complete: it goes to the host ahead of the resampling and the shift, which only the
  // next frame needs (they run while the host takes the estimate).
  buffers_.estimate.download_enqueued(std::span<float>(buffers_.estimate_host));
  // With the fit, the children are moved by its correction as they are gathered.
  steps_->resample(frame_, centre, refiner_ ? refiner_->correction() : buffers_.no_correction, refiner_ != nullptr,
                   events);
  batch.submit();
  events.timings.enqueue_ms = p->clock.elapsed_ms();
  pending_ = std::move(p);
}

Estimate DeviceFilter::collect() {
  if (!pending_) throw InputError("device filter: collect() without an enqueued update");
  const std::unique_ptr<Pending> p = std::move(pending_);
  Estimate e;
  e.timings = p->events.timings;
  const Stopwatch wait;
  queue_->wait_enqueued_reads();  // the frame's one wait
  e.timings.wait_ms = wait.elapsed_ms();
  const float* est = buffers_.estimate_host.data();
  e.pose = Pose({est[DT_EST_TX], est[DT_EST_TX + 1], est[DT_EST_TX + 2]},
                Eigen::Quaterniond(est[DT_EST_QW], est[DT_EST_QW + 1], est[DT_EST_QW + 2], est[DT_EST_QW + 3]));
  e.linear_velocity = Eigen::Vector3d(est[DT_EST_VX], est[DT_EST_VX + 1], est[DT_EST_VX + 2]);
  e.angular_velocity = Eigen::Vector3d(est[DT_EST_WX], est[DT_EST_WX + 1], est[DT_EST_WX + 2]);
  e.effective_sample_size = est[DT_EST_ESS];
  e.max_log_likelihood = est[DT_EST_MAX_LL];
  e.mean_log_likelihood = est[DT_EST_MEAN_LL];
  e.resampled = est[DT_EST_RESAMPLE] != 0.0f;
  if (refiner_) {
    // The fit's H (float sums) made into the covariance here, in double, as the reference makes it.
    Eigen::Matrix<double, 6, 6> h;
    for (int r = 0, k = 0; r < 6; ++r)
      for (int c = 0; c <= r; ++c, ++k) h(r, c) = h(c, r) = est[DT_EST_NORMAL + k];
    e.covariance =
        model::fit_covariance(h, static_cast<int>(est[DT_EST_FIT_PIXELS]), refiner_->radius(), config_.refine);
    e.refine_iterations = static_cast<int>(est[DT_EST_REFINE_ITERATIONS]);
    // Counts, exact in float: the share as the reference divides them.
    e.confidence = est[DT_EST_MEASURED] > 0 ? static_cast<double>(est[DT_EST_VISIBLE]) / est[DT_EST_MEASURED] : 0.0;
  }
  last_resampled_ = e.resampled;
  weighed_in_scratch_ = true;
  next_window_ = model::next_state_window(window_, config_, extent_, e.pose, camera_, rows_.pixel_limit());

  if (config_.step_timings) read_step_times(p->events, e.timings);
  e.timings.total_ms = p->clock.elapsed_ms();
  ++frame_;
  return e;
}

// The steps' device times from their events, once the frame is done.
void DeviceFilter::read_step_times(FrameEvents& events, StepTimings& timings) const {
  if (events.propagated) timings.propagate_ms = events.propagated->elapsed_ms();
  for (const auto& event : events.rendered)
    if (event) {
      timings.render_ms += event->elapsed_ms();
      timings.render_on_device = true;
    }
  for (const auto& event : events.weighed) timings.weigh_ms += event->elapsed_ms();
  timings.resample_ms += device_span_ms(events.summarized);
  for (const auto& event : events.resampling) timings.resample_ms += event->elapsed_ms();
  // The fit's launches as one span on the device (the spread layout enqueues dozens); the cloud's shift
  // is part of resample_particles, in resample_ms.
  if (!events.refined.empty()) timings.refine_ms = device_span_ms(events.refined);
}

}  // namespace depthtrack
