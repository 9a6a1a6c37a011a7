#include "filter/device_refiner.hpp"

#include <algorithm>
#include <cstdint>
#include <depthtrack/error.hpp>
#include <stdexcept>

#include "compute/program_cache.hpp"
#include "dt_launch.h"
#include "dt_refine_state.h"
#include "dt_state.h"
#include "filter/kernels/refine_args.hpp"
#include "model/fit_noise.hpp"
#include "model/kernel_params.hpp"

namespace depthtrack {

namespace {
// Work-items of the fit's groups. 128 (the filter's) left the one group's loops ~38 of the 80x60
// pixels and ~7 triangles per rendering in sequence; 256 halves that and keeps the 29 sums' local
// memory (29.7 KB) within CUDA's 48 KB of static shared memory and the registers within a
// multiprocessor. The spread layout's sums kernel uses the same size (its per-group tree).
constexpr size_t kRefineGroup = DT_REFINE_GROUP;
constexpr size_t kLinearGroup = DT_LINEAR_GROUP;  // the spread layout's draws: a work-item per triangle and slice
// The spread sums kernel: enough groups for every pixel of the image to have its own work-item, at
// most this many rows of partials for its last group to add (beyond 256 x 256 pixels a work-item
// sums several).
constexpr size_t kMaxSumGroups = 256;
// Pixels each work-item of the spread sums kernel adds: fewer groups leave fewer rows of partials for
// the last group's one work-item to add (19 rows at 80x60 with a pixel each, 5 with 4).
constexpr size_t kSumPixelsPerItem = 4;
static_assert(kRefineGroup >= DT_REFINE_SUMS);  // a group writes its row of partials a sum per work-item

size_t round_up(size_t n, size_t multiple) {
  return (n + multiple - 1) / multiple * multiple;
}

}  // namespace

// What each layout costs at 2,000 particles, 80x60 (refine_ms, one group / spread): the spread layout is
// 19 short launches (a draw and the sums per evaluation; it was 37 with separate id and step kernels),
// the one group loops over the mesh's triangles per work-item twice per rendering.
//   handset (842 triangles): PoCL (2 cores) 1.14 / 1.34 ms; H200 CUDA 0.202 / 0.149; H200 NVIDIA
//     OpenCL 0.168 / 0.176 (its launches cost more than CUDA's);
//   YCB mug (16,384): PoCL 6.1 / 2.7; H200 CUDA 1.01 / 0.150; NVIDIA OpenCL 0.92 / 0.149.
// (H200: the 19-launch layout with a fence in place of the rows' stamps.) The
// threshold lies between the two meshes and was not measured itself. With 4 pixels a work-item in the
// sums (5 rows for the last group), spread is faster on NVIDIA OpenCL too: handset 0.138 /
// 0.158 ms spread / one group, the mug simplified to 3,196 triangles 0.153 / 0.271; so every GPU spreads.
// Measured: the spread layout's draw and sums in one group (one-launch) against spread,
// untimed frame at 2,000 particles (H100): NVIDIA OpenCL handset 0.46-0.55 ->
// 0.38-0.42 ms, the mug simplified to 412 / 1,120 / 3,196 triangles 0.45-0.47 -> 0.42-0.43, 0.47-0.54 ->
// 0.43-0.44, 0.48-0.54 -> 0.49-0.56 (its host's launches are the frame's cost there); CUDA, whose graphs make launches
// cheap, slower for every mesh (handset 0.24-0.27 -> 0.24-0.32). PoCL (2 cores) handset refine_ms 0.79-0.81 against
// 1.16-1.35 one group and 1.31-1.60 spread; the 16,384-triangle mug 3.4-3.5 against spread's 2.7-3.4.
// Once OpenCL's transfers went through pinned memory (0.1 ms less host time a frame for either layout)
// the one group's device time decided the 3,196-triangle mug: 0.455 ms against spread's 0.44-0.51
// before. So below 2,048 triangles every device whose launches are not replayed (CUDA's are:
// DeviceInfo::replayed_launches) fits in one launch (not measured between
// 1,120 and 3,196). PoCL at 200 particles, refine_ms one-launch / spread / one-group: 160x120 0.99 / 1.99 /
// 1.46, 320x240 1.83 / 4.00 / 2.78; on a GPU the one group's pixel loop grows with the image
// (kOneLaunchGpuPixels).
RefineLayout resolved_refine_layout(RefineLayout layout, const compute::DeviceInfo& device, size_t triangle_count,
                                    size_t pixel_count) {
  if ((layout == RefineLayout::Spread || layout == RefineLayout::OneLaunch) && !device.int64_atomics)
    throw InputError("refinement layout " + std::string(to_string(layout)) +
                     " needs 64-bit atomic min (cl_khr_int64_extended_atomics), which " + device.name +
                     " does not list; use --refine-layout one-group or auto");
  if (layout != RefineLayout::Auto) return layout;
  if (!device.int64_atomics) return RefineLayout::OneGroup;
  if (triangle_count >= kSpreadTriangles || device.replayed_launches) return RefineLayout::Spread;
  if (device.is_gpu && pixel_count > kOneLaunchGpuPixels) return RefineLayout::Spread;
  return RefineLayout::OneLaunch;
}

unsigned refine_draw_slices(RefineLayout layout, size_t triangle_count, int image_height, bool gpu) {
  if (!gpu || triangle_count == 0) return 1;
  const size_t wanted = layout == RefineLayout::Spread ? (kFitDrawItems + triangle_count - 1) / triangle_count
                                                       : kRefineGroup / triangle_count;
  const size_t most = std::clamp<size_t>(static_cast<size_t>(std::max(image_height, 1)), 1, kMaxDrawSlices);
  return static_cast<unsigned>(std::clamp<size_t>(wanted, 1, most));
}

DeviceRefiner::DeviceRefiner(compute::Queue& queue, compute::ProgramCache& programs, const Mesh& mesh,
                             const Camera& camera, const TrackerConfig& config, const std::string& occlusion_definition,
                             unsigned draw_slices)
    : queue_(queue),
      stages_(model::fit_stages(config)),
      config_(stages_.front()),
      camera_(camera),
      centre_(mesh.centre().cast<double>()),
      radius_(mesh.radius()),
      layout_(resolved_refine_layout(config.refine.layout, queue.info(), mesh.triangles.size(),
                                     static_cast<size_t>(camera.pixel_count()))),
      draw_slices_(draw_slices > 0
                       ? draw_slices
                       : refine_draw_slices(layout_, mesh.triangles.size(), camera.height, queue.info().is_gpu)),
      program_(programs.program(layout_ == RefineLayout::OneGroup ? "refine.cl" : "refine_spread.cl",
                                {"DT_GROUP_SIZE=" + std::to_string(kRefineGroup), occlusion_definition})),
      mesh_(queue, mesh),
      correction_(queue, 6) {
  if (layout_ == RefineLayout::OneGroup) {
    refine_ = program_->kernel("refine");
    pose_ = compute::Buffer<float>(queue, DT_STATE_STRIDE);
    tile_ = compute::Buffer<unsigned>(queue, static_cast<size_t>(camera.pixel_count()));
    ids_ = compute::Buffer<unsigned>(queue, static_cast<size_t>(camera.pixel_count()));
    return;
  }
  const size_t pixels = static_cast<size_t>(camera.pixel_count());
  fit_state_ = compute::Buffer<float>(queue, sizeof(dt_refine_state) / sizeof(float));
  fit_state_.upload(std::vector<float>(fit_state_.size(), 0.0f));
  if (layout_ == RefineLayout::OneLaunch) {
    refine_ = program_->kernel("refine_one_launch");
  } else {
    begin_ = program_->kernel("refine_begin");
    draw_ = program_->kernel("refine_draw");
    sums_ = program_->kernel("refine_sums");
    const size_t per_group = kRefineGroup * kSumPixelsPerItem;
    sum_groups_ = std::clamp<size_t>((pixels + per_group - 1) / per_group, 1, kMaxSumGroups);
    // Stamp 0 in the state and rows unwritten: no row counts as written before its group writes it
    // (refine_spread.cl's refine_sums).
    partials_ = compute::Buffer<uint64_t>(queue, sum_groups_ * DT_REFINE_SUMS);
    partials_.upload(std::vector<uint64_t>(partials_.size(), DT_ROW_UNWRITTEN));
  }
  // Neither spread layout clears: every evaluation resets the pixels it drew (refine_spread.cl).
  nearest_ = compute::Buffer<uint64_t>(queue, pixels);
  nearest_.upload(std::vector<uint64_t>(pixels, DT_NEAREST_EMPTY));
}

std::vector<compute::EventPtr> DeviceRefiner::refine(compute::Buffer<float>& estimate, const RefineInputs& in,
                                                     const SummaryInputs* summary) {
  if (summary && !summarizes_first())
    throw std::logic_error("device refiner: the " + std::string(to_string(layout_)) + " layout does not summarize");
  const dt_refine_args args =
      model::refine_params(stages_, centre_, radius_, mesh_.vertices.size() / 3, in.time, in.dt, draw_slices_);
  if (layout_ == RefineLayout::Spread) return refine_spread(estimate, in, args);
  const kernels::Launch one_group{queue_, *refine_, compute::NdRange::linear(kRefineGroup, kRefineGroup),
                                  config_.step_timings};
  const kernels::FitFrame frame{in.states, in.observed, in.occlusion, in.occlusion_time, in.frame_times, in.parents};
  const kernels::FitMesh mesh{mesh_.vertices, mesh_.triangles, mesh_.planes, mesh_.triangle_count()};
  const dt_camera cam = model::camera_params(camera_, config_, mesh_.cull_back_faces);
  const dt_model model = model::model_params(config_);
  compute::EventPtr fit;
  if (layout_ == RefineLayout::OneLaunch) {
    // Without a summary to make, its buffers are not read: estimate stands in for them.
    const Eigen::Vector3f centre = summary ? summary->centre : Eigen::Vector3f::Zero();
    fit = kernels::launch(one_group,
                          kernels::RefineOneLaunchArgs{.log_weight = summary ? summary->log_weight : estimate,
                                                       .log_likelihood = summary ? summary->log_likelihood : estimate,
                                                       .weights = summary ? summary->weights : estimate,
                                                       .count = summary ? summary->count : 0u,
                                                       .centre_x = centre.x(),
                                                       .centre_y = centre.y(),
                                                       .centre_z = centre.z(),
                                                       .kl_threshold = summary ? summary->kl_threshold : 0.0f,
                                                       .summarize = static_cast<unsigned>(summary != nullptr),
                                                       .fit_state = fit_state_,
                                                       .estimate = estimate,
                                                       .frame = frame,
                                                       .mesh = mesh,
                                                       .cam = cam,
                                                       .model = model,
                                                       .args = args,
                                                       .window = in.window,
                                                       .nearest = nearest_,
                                                       .correction = correction_});
  } else {
    fit = kernels::launch(one_group, kernels::RefineOneGroupArgs{.estimate = estimate,
                                                                 .frame = frame,
                                                                 .mesh = mesh,
                                                                 .cam = cam,
                                                                 .model = model,
                                                                 .args = args,
                                                                 .pose_state = pose_,
                                                                 .tile = tile_,
                                                                 .ids = ids_,
                                                                 .correction = correction_,
                                                                 .window = in.window});
  }
  if (!fit) return {};
  return {fit};
}

// begin, then iterations + 1 evaluations (draw, sums) per stage with no wait: the sums kernel's last group
// stops the fit on the device, and what follows returns at once.
std::vector<compute::EventPtr> DeviceRefiner::refine_spread(compute::Buffer<float>& estimate, const RefineInputs& in,
                                                            const dt_refine_args& args) {
  const dt_camera cam = model::camera_params(camera_, config_, mesh_.cull_back_faces);
  const dt_model model = model::model_params(config_);
  const auto per_item = compute::NdRange::linear(
      round_up(std::max<size_t>(mesh_.triangle_count() * size_t{draw_slices_}, 1), kLinearGroup), kLinearGroup);
  const auto over_pixels = compute::NdRange::linear(sum_groups_ * kRefineGroup, kRefineGroup);
  const unsigned triangles = mesh_.triangle_count();
  // Timed: begin and the last sums, which the filter reads as one span (Event::elapsed_since_ms);
  // the launches between them untimed. Each kernel's arguments are set once: the evaluations differ
  // only in the fit's state on the device, and the frame's time and window reach the fit through
  // begin (dt_refine_state), so that only begin's arguments change from frame to frame.
  std::vector<compute::EventPtr> events;
  const bool timed = config_.step_timings;
  if (compute::EventPtr begun = kernels::launch(
          {queue_, *begin_, compute::NdRange::linear(1, 1), timed},
          kernels::RefineBeginArgs{
              .fit_state = fit_state_, .estimate = estimate, .states = in.states, .args = args, .window = in.window}))
    events.push_back(std::move(begun));
  kernels::set_args(*draw_, kernels::RefineDrawArgs{.fit_state = fit_state_,
                                                    .mesh = {mesh_.vertices, mesh_.triangles, mesh_.planes, triangles},
                                                    .cam = cam,
                                                    .nearest = nearest_});
  kernels::set_args(*sums_, kernels::RefineSumsArgs{.fit_state = fit_state_,
                                                    .estimate = estimate,
                                                    .frame = {in.states, in.observed, in.occlusion, in.occlusion_time,
                                                              in.frame_times, in.parents},
                                                    .planes = mesh_.planes,
                                                    .triangle_count = triangles,
                                                    .cam = cam,
                                                    .model = model,
                                                    .nearest = nearest_,
                                                    .partials = partials_,
                                                    .correction = correction_});
  const int evaluations = static_cast<int>(stages_.size()) * (config_.refine.iterations + 1);
  for (int evaluation = 0; evaluation < evaluations; ++evaluation) {
    queue_.launch_untimed(*draw_, per_item);
    if (compute::EventPtr last =
            compute::launch_timed_if(timed && evaluation + 1 == evaluations, queue_, *sums_, over_pixels))
      events.push_back(std::move(last));
  }
  return events;
}

}  // namespace depthtrack
