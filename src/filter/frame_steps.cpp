#include "filter/frame_steps.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <variant>

#include "dt_time_index.h"
#include "filter/kernels/particle_args.hpp"
#include "filter/kernels/resample_args.hpp"
#include "filter/kernels/summary_args.hpp"
#include "filter/kernels/weigh_args.hpp"
#include "filter/wide_summary.hpp"
#include "model/kernel_params.hpp"
#include "philox.h"

namespace depthtrack {

struct FrameSteps::Kernels {
  std::shared_ptr<compute::Program> resample_program, initialize_program, weigh_program, propagate_program,
      summarize_program;
  std::unique_ptr<compute::Kernel> weigh, propagate, summarize, prefix_sum, resample_particles, resample_scanning,
      gather_states, identity_parents, fill, initialize_particles, fill_per_particle, fill_time_indices,
      retire_time_indices;
  std::unique_ptr<compute::Kernel> render_weigh[2];  // [propagate_in_weigh]
};

namespace {
std::string group_size(size_t items) {
  return "DT_GROUP_SIZE=" + std::to_string(items);
}
}  // namespace

FrameSteps::FrameSteps(compute::Queue& queue, compute::ProgramCache& programs, const FramePlan& plan,
                       std::span<const FramePlan> layouts, const TrackerConfig& config, const Camera& camera,
                       AtlasSource& atlas, FilterBuffers& buffers, StateRows& rows, FrameTimeTable& times)
    : queue_(queue),
      plan_(plan),
      config_(config),
      camera_(camera),
      atlas_(atlas),
      b_(buffers),
      rows_(rows),
      times_(times),
      k_(std::make_unique<Kernels>()) {
  const std::string occlusion = model::occlusion_definition(config.occlusion_storage);
  const std::vector<std::string> defines = {
      group_size(kFilterGroup), occlusion,
      plan.whole_image_state ? "DT_WHOLE_IMAGE_STATE=1" : "DT_WHOLE_IMAGE_STATE=0"};
  Kernels& k = *k_;
  k.resample_program = programs.program("resample.cl", defines);
  for (const FramePlan& layout : layouts) {
    if (layout.summary == SummaryStep::Wide && !wide_)  // sized for the most particles, the last layout's
      wide_ = std::make_unique<WideSummary>(queue, programs, occlusion, layouts.back().particles);
    if (layout.resample == ResampleStep::PrefixSum && !k.prefix_sum)
      k.prefix_sum = k.resample_program->kernel("prefix_sum");
    if (layout.resample == ResampleStep::Scanning && !k.resample_scanning)
      k.resample_scanning = k.resample_program->kernel("resample_scanning");
    if (layout.resample != ResampleStep::Scanning && !k.resample_particles)
      k.resample_particles = k.resample_program->kernel("resample_particles");
  }
  k.gather_states = k.resample_program->kernel("gather_states");
  k.identity_parents = k.resample_program->kernel("identity_parents");
  k.fill = k.resample_program->kernel("fill");
  k.initialize_program = programs.program("initialize.cl", defines);
  k.initialize_particles = k.initialize_program->kernel("initialize_particles");
  k.fill_per_particle = k.initialize_program->kernel("fill_per_particle");
  if (config.occlusion_storage == OcclusionStorage::PerPixelTime) {  // cl/time_index.cl, in resample.cl's program
    k.fill_time_indices = k.resample_program->kernel("fill_time_indices");
    k.retire_time_indices = k.resample_program->kernel("retire_time_indices");
  }
  if (plan.weigh == WeighStep::RenderWeigh) {
    if (!atlas.device_mesh()) throw std::logic_error("frame plan: render_weigh without the atlas source's device mesh");
    const RenderWeighLayout& layout = plan.render_weigh;
    for (const FramePlan& l : layouts) {
      std::unique_ptr<compute::Kernel>& kernel = k.render_weigh[l.propagate_in_weigh ? 1 : 0];
      if (kernel) continue;
      kernel = programs
                   .program("render_weigh.cl",
                            {defines[0], defines[1], defines[2], "DT_TILE_PIXELS=" + std::to_string(layout.tile_pixels),
                             "DT_SHARED_POINTS=" + std::to_string(layout.shared_points),
                             "DT_PROPAGATE_INSIDE=" + std::string(l.propagate_in_weigh ? "1" : "0"),
                             "DT_RESIDENT_GROUPS=" + std::to_string(layout.resident_groups)})
                   ->kernel("render_weigh");
    }
  } else {  // the atlas drawn by its source (only each pose's box where it can), then weighed
    k.weigh_program = programs.program("weigh.cl", defines);
    k.weigh = k.weigh_program->kernel("weigh");
    atlas.draw_boxed();
    if (!atlas.tile_boxes()) buffers.unused_boxes = compute::Buffer<unsigned>(queue, 4);  // whole tiles
  }
  if (std::any_of(layouts.begin(), layouts.end(), [](const FramePlan& l) { return l.builds_propagate(); })) {
    k.propagate_program = programs.program("propagate.cl", defines);
    k.propagate = k.propagate_program->kernel("propagate");
  }
  for (const FramePlan& layout : layouts)
    if (const auto summary = layout.summary_kernel(); summary && !k.summarize) {
      std::vector<std::string> summary_defines = defines;
      summary_defines.front() = group_size(layout.summary_group);
      k.summarize_program = programs.program("summarize.cl", summary_defines);
      k.summarize = k.summarize_program->kernel(
          std::visit([](auto kernel) { return decltype(kernel)::Arguments::kernel; }, *summary));
    }
}

FrameSteps::~FrameSteps() = default;

void FrameSteps::initialize(std::span<const float> modes, const dt_initial& spread, size_t state_pixels) {
  compute::Buffer<float> mode_buffer(queue_, modes.size());
  mode_buffer.upload(modes);
  const unsigned count = static_cast<unsigned>(plan_.particles);
  kernels::launch({queue_, *k_->initialize_particles, plan_.per_particle()},
                  kernels::InitializeParticlesArgs{.state = b_.state,
                                                   .count = count,
                                                   .seed_lo = static_cast<unsigned>(config_.seed & 0xffffffffu),
                                                   .seed_hi = static_cast<unsigned>(config_.seed >> 32),
                                                   .modes = mode_buffer,
                                                   .spread = spread});
  kernels::launch({queue_, *k_->fill, plan_.per_particle()},
                  kernels::FillArgs{.values = b_.log_weight, .count = count, .value = 0.0f});
  identity_parents();
  const auto per_particle_group = plan_.group_per_particle(plan_.particles);
  if (config_.occlusion_storage != OcclusionStorage::Off)
    kernels::launch({queue_, *k_->fill_per_particle, per_particle_group},
                    kernels::FillPerParticleArgs{.values = rows_.occlusion,
                                                 .pixels = static_cast<unsigned>(state_pixels),
                                                 .value = static_cast<float>(config_.occlusion.initial)});
  if (config_.occlusion_storage == OcclusionStorage::PerPixelTime) {
    kernels::launch({queue_, *k_->fill_time_indices, per_particle_group},
                    kernels::FillTimeIndicesArgs{.indices = rows_.time,
                                                 .pixels = static_cast<unsigned>(state_pixels),
                                                 .value = static_cast<unsigned>(DT_TIME_NEVER)});
    times_.reset();
  }
  queue_.finish();
}

void FrameSteps::identity_parents() {
  kernels::launch({queue_, *k_->identity_parents, plan_.per_particle()},
                  kernels::IdentityParentsArgs{.parents = b_.parents, .count = static_cast<unsigned>(plan_.particles)});
}

// Where render_weigh moves each particle itself (a small cloud: one launch fewer) propagate_ms is part
// of weigh_ms.
void FrameSteps::propagate(const FrameInputs& in, FrameEvents& events) {
  if (!in.moves || plan_.propagate_in_weigh) return;
  events.propagated =
      kernels::launch({queue_, *k_->propagate, plan_.per_particle(), config_.step_timings},
                      kernels::PropagateArgs{.state = b_.state,
                                             .count = static_cast<unsigned>(plan_.particles),
                                             .seed_lo = static_cast<unsigned>(config_.seed & 0xffffffffu),
                                             .seed_hi = static_cast<unsigned>(config_.seed >> 32),
                                             .frame = in.frame,
                                             .motion = in.motion});
}

// Rare (cl/dt_time_index.h), so untimed.
void FrameSteps::retire_time_indices(size_t rows, size_t state_pixels, unsigned now_index) {
  kernels::launch(
      {queue_, *k_->retire_time_indices, compute::NdRange::linear(256 * kFilterGroup, kFilterGroup), false},
      kernels::RetireTimeIndicesArgs{
          .indices = rows_.time, .count = static_cast<uint64_t>(rows * state_pixels), .now_index = now_index});
}

// Each particle's occlusion rows from its parent's row (the last frame's resampling) into its own row of
// the scratch buffers; the rows move with the state window.
void FrameSteps::weigh(const FrameInputs& in, bool keep_atlas, FrameEvents& events) {
  const dt_model model = model::model_params(config_);
  if (plan_.weigh == WeighStep::RenderWeigh) {
    const MeshBuffers& mesh = *atlas_.device_mesh();
    events.weighed.push_back(kernels::launch(
        {queue_, *k_->render_weigh[plan_.propagate_in_weigh ? 1 : 0], plan_.group_per_particle(plan_.particles),
         config_.step_timings},
        kernels::RenderWeighArgs{.states = b_.state,
                                 .vertices = mesh.vertices,
                                 .triangles = mesh.triangles,
                                 .planes = mesh.planes,
                                 .triangle_count = mesh.triangle_count(),
                                 .vertex_count = mesh.vertex_count(),
                                 .cam = model::camera_params(camera_, config_, mesh.cull_back_faces),
                                 .observed = b_.observed,
                                 .parents = b_.parents,
                                 .occlusion_from = rows_.occlusion,
                                 .time_from = rows_.time,
                                 .occlusion_to = rows_.scratch_occlusion,
                                 .time_to = rows_.scratch_time,
                                 .frame_times = times_.device(),
                                 .log_likelihood = b_.log_likelihood,
                                 .log_weight = b_.log_weight,
                                 .model = model,
                                 .now = in.now,
                                 .now_index = in.now_index,
                                 .dt = in.dt,
                                 .atlas = b_.atlas,
                                 .keep_atlas = static_cast<unsigned>(keep_atlas),
                                 .window = in.window,
                                 .propagate = static_cast<unsigned>(in.moves && plan_.propagate_in_weigh),
                                 .seed_lo = static_cast<unsigned>(config_.seed & 0xffffffffu),
                                 .seed_hi = static_cast<unsigned>(config_.seed >> 32),
                                 .frame = in.frame,
                                 .motion = in.motion}));
    return;
  }
  // The atlas' tiles drawn and weighed in turns where it holds fewer than the particles.
  const size_t count = plan_.particles, tiles = atlas_.layout().tiles();
  const compute::Buffer<unsigned>* boxes = atlas_.tile_boxes();
  for (size_t first = 0; first < count; first += tiles) {
    const size_t n = std::min(tiles, count - first);
    events.rendered.push_back(tiles >= count ? atlas_.draw(b_.state, b_.atlas, events.timings)
                                             : atlas_.draw_range(b_.state, b_.atlas, first, n));
    events.weighed.push_back(kernels::launch({queue_, *k_->weigh, plan_.group_per_particle(n), config_.step_timings},
                                             kernels::WeighArgs{.atlas = b_.atlas,
                                                                .observed = b_.observed,
                                                                .parents = b_.parents,
                                                                .occlusion_from = rows_.occlusion,
                                                                .time_from = rows_.time,
                                                                .occlusion_to = rows_.scratch_occlusion,
                                                                .time_to = rows_.scratch_time,
                                                                .frame_times = times_.device(),
                                                                .log_likelihood = b_.log_likelihood,
                                                                .log_weight = b_.log_weight,
                                                                .pixels = static_cast<unsigned>(plan_.pixels),
                                                                .model = model,
                                                                .now = in.now,
                                                                .now_index = in.now_index,
                                                                .dt = in.dt,
                                                                .layout = atlas_.layout().kernel_args(),
                                                                .window = in.window,
                                                                .boxes = boxes ? *boxes : b_.unused_boxes,
                                                                .boxed = static_cast<unsigned>(boxes != nullptr),
                                                                .first = static_cast<unsigned>(first)}));
  }
}

void FrameSteps::summarize(const Eigen::Vector3f& centre, float kl_threshold, unsigned karcher_steps,
                           FrameEvents& events) {
  if (plan_.summary == SummaryStep::Wide) {
    events.summarized = wide_->summarize(plan_.particles, b_.state, b_.log_weight, b_.log_likelihood, b_.weights,
                                         b_.estimate, centre.x(), centre.y(), centre.z(), kl_threshold, karcher_steps);
  } else if (const auto summary = plan_.summary_kernel()) {
    const kernels::SummaryInputs inputs{.state = b_.state,
                                        .log_weight = b_.log_weight,
                                        .log_likelihood = b_.log_likelihood,
                                        .weights = b_.weights,
                                        .estimate = b_.estimate,
                                        .count = static_cast<unsigned>(plan_.particles),
                                        .centre_x = centre.x(),
                                        .centre_y = centre.y(),
                                        .centre_z = centre.z(),
                                        .kl_threshold = kl_threshold,
                                        .karcher_steps = karcher_steps};
    const kernels::Launch where{queue_, *k_->summarize, plan_.one_group(plan_.summary_group), config_.step_timings};
    events.summarized = {std::visit(
        [&](auto kernel) { return kernels::launch(where, decltype(kernel)::Arguments::from(inputs)); }, *summary)};
  }
}

// Enqueued every frame; the kernels read the device's decision (estimate[DT_EST_RESAMPLE]). The state is
// gathered, or copied without resampling, into the scratch buffer, which becomes the state: the weighed
// states stay in scratch_state. The per-pixel state is not copied: parents keeps the choice (the identity
// without resampling) and the next frame's weigh reads each row from its parent.
void FrameSteps::resample(unsigned frame, const Eigen::Vector3f& centre, const compute::Buffer<float>& correction,
                          bool shift, FrameEvents& events) {
  const dt_philox4 words = dt_random_words(config_.seed, 0u, frame, DT_STREAM_RESAMPLE, 0u);
  const unsigned count = static_cast<unsigned>(plan_.particles);
  const float u = dt_uniform01(words.v[0]);
  std::vector<compute::EventPtr>& out = events.resampling;
  const bool scanning = plan_.resample == ResampleStep::Scanning;
  const kernels::ResampleArgs args{.weights = scanning ? b_.weights : b_.cumulative,
                                   .parents = b_.parents,
                                   .count = count,
                                   .u = u,
                                   .estimate = b_.estimate,
                                   .from = b_.state,
                                   .to = b_.scratch_state,
                                   .log_weight = b_.log_weight,
                                   .correction = correction,
                                   .centre_x = centre.x(),
                                   .centre_y = centre.y(),
                                   .centre_z = centre.z(),
                                   .shift = static_cast<unsigned>(shift)};
  if (scanning) {
    out.push_back(kernels::launch({queue_, *k_->resample_scanning, plan_.scanning(), config_.step_timings}, args));
  } else {
    if (plan_.resample == ResampleStep::WidePrefixSum)
      out = wide_->prefix_sum(plan_.particles, b_.weights, b_.cumulative, b_.estimate);
    else
      out.push_back(kernels::launch(
          {queue_, *k_->prefix_sum, plan_.one_group(kFilterGroup), config_.step_timings},
          kernels::PrefixSumArgs{
              .values = b_.weights, .cumulative = b_.cumulative, .count = count, .estimate = b_.estimate}));
    out.push_back(kernels::launch({queue_, *k_->resample_particles, plan_.per_particle(), config_.step_timings}, args));
  }
  std::swap(b_.state, b_.scratch_state);
}

// Child j of the new count takes particle choice[j]'s kinematic state, gathered into the scratch buffer,
// which becomes the state, with its log weight at 0; the parents are set from the host.
void FrameSteps::gather(const compute::Buffer<unsigned>& choice, size_t count) {
  const unsigned n = static_cast<unsigned>(count);
  kernels::launch({queue_, *k_->gather_states, plan_.per_particle()},
                  kernels::GatherStatesArgs{.choice = choice, .count = n, .from = b_.state, .to = b_.scratch_state});
  kernels::launch({queue_, *k_->fill, plan_.per_particle()},
                  kernels::FillArgs{.values = b_.log_weight, .count = n, .value = 0.0f});
  std::swap(b_.state, b_.scratch_state);
}

}  // namespace depthtrack
