#include "filter/device_pose_scorer.hpp"

#include <algorithm>
#include <string>

#include "atlas/raster_inputs.hpp"
#include "compute/program_cache.hpp"
#include "core/pose_state.hpp"
#include "dt_launch.h"
#include "dt_state.h"
#include "filter/kernels/score_args.hpp"
#include "model/kernel_params.hpp"
#include "model/occlusion_chain.hpp"

namespace depthtrack {

namespace {
constexpr size_t kScoreGroup = DT_FILTER_GROUP;      // work-items per pose in cl/score.cl, as in weigh
constexpr size_t kRasterizeGroup = DT_FILTER_GROUP;  // per pose in cl/rasterize.cl, as the kernel atlas source
constexpr size_t kBoxGroup = 64;  // per pose in cl/visible_box.cl: a coarse mesh's hundreds of vertices
// Poses per launch at most: enough to fill a GPU at 80x60; a CPU device gains nothing from more.
constexpr size_t kGpuBatch = 4096, kCpuBatch = 256;

// As many poses as a fifth of device memory holds (atlas tile and state each), at most the above.
size_t batch_for(const compute::Queue& queue, size_t pixels) {
  const size_t most = queue.info().is_gpu ? kGpuBatch : kCpuBatch;
  const double per_pose = 4.0 * (static_cast<double>(pixels) + DT_STATE_STRIDE + 1);
  const double memory = static_cast<double>(queue.info().global_memory);
  if (memory <= 0) return most;
  return std::clamp<size_t>(static_cast<size_t>(0.2 * memory / per_pose), 1, most);
}
}  // namespace

DevicePoseScorerPrograms::DevicePoseScorerPrograms(compute::ProgramCache& programs)
    : rasterize(programs.program("rasterize.cl", rasterize_definitions(kRasterizeGroup, programs.queue().info()))),
      score(programs.program("score.cl", {"DT_GROUP_SIZE=" + std::to_string(kScoreGroup)})),
      visible_box(programs.program("visible_box.cl", {"DT_GROUP_SIZE=" + std::to_string(kBoxGroup)})) {}

DevicePoseScorer::DevicePoseScorer(compute::Queue& queue, std::shared_ptr<const DevicePoseScorerPrograms> programs,
                                   const Mesh& mesh, const Camera& camera, const TrackerConfig& config)
    : queue_(queue),
      programs_(std::move(programs)),
      config_(config),
      pixels_(static_cast<size_t>(camera.pixel_count())),
      batch_(batch_for(queue, pixels_)),
      // Particle-major: tile i is the i-th block of pixels, whatever the batch's fill.
      layout_(render::AtlasLayout::particle_major(static_cast<int>(batch_), camera.width, camera.height)),
      mesh_(queue, mesh),
      camera_(model::camera_params(camera, config, mesh_.cull_back_faces)),
      rasterize_(programs_->rasterize->kernel("rasterize")),
      score_(programs_->score->kernel("score")),
      visible_box_(programs_->visible_box->kernel("visible_box")) {}

DevicePoseScorer::~DevicePoseScorer() = default;

void DevicePoseScorer::allocate() {
  if (atlas_.size() > 0) return;
  states_ = compute::Buffer<float>(queue_, batch_ * DT_STATE_STRIDE);
  atlas_ = compute::Buffer<float>(queue_, layout_.floats());
  observed_ = compute::Buffer<float>(queue_, pixels_);
  scores_ = compute::Buffer<float>(queue_, batch_);
  boxes_ = compute::Buffer<float>(queue_, 4 * batch_);
  unused_boxes_ = compute::Buffer<unsigned>(queue_, 4);  // whole tiles: score.cl reads every pixel
}

dt_model DevicePoseScorer::model_for(const ObservationModel& observation) const {
  TrackerConfig config = config_;
  config.observation = observation;
  return model::model_params(config);
}

void DevicePoseScorer::upload_batch(std::span<const Pose> poses, std::vector<float>& packed) {
  packed.assign(poses.size() * DT_STATE_STRIDE, 0.0f);
  for (size_t i = 0; i < poses.size(); ++i) write_pose(poses[i], packed.data() + i * DT_STATE_STRIDE);
  states_.upload(std::span<const float>(packed.data(), packed.size()));
}

std::vector<double> DevicePoseScorer::score(std::span<const Pose> poses, const DepthImage& depth,
                                            const ObservationModel& observation) {
  allocate();
  observed_.upload(depth.data());
  const dt_model model = model_for(observation);
  const float p = static_cast<float>(model::fresh_occlusion(config_));
  std::vector<double> out;
  out.reserve(poses.size());
  std::vector<float> packed, scores(batch_);
  for (size_t first = 0; first < poses.size(); first += batch_) {
    const size_t n = std::min(batch_, poses.size() - first);
    upload_batch(poses.subspan(first, n), packed);
    kernels::launch(
        {queue_, *rasterize_, compute::NdRange::linear(n * kRasterizeGroup, kRasterizeGroup)},
        kernels::rasterize_args(mesh_, camera_, layout_.kernel_args(), states_, atlas_, unused_boxes_, 0u, 0u));
    kernels::launch({queue_, *score_, compute::NdRange::linear(n * kScoreGroup, kScoreGroup)},
                    kernels::ScoreArgs{.atlas = atlas_,
                                       .observed = observed_,
                                       .scores = scores_,
                                       .pixels = static_cast<unsigned>(pixels_),
                                       .model = model,
                                       .p = p,
                                       .layout = layout_.kernel_args()});
    scores_.download(std::span<float>(scores.data(), n));
    out.insert(out.end(), scores.begin(), scores.begin() + static_cast<std::ptrdiff_t>(n));
  }
  return out;
}

std::vector<float> DevicePoseScorer::visible_boxes(std::span<const Pose> poses, const DepthImage& depth,
                                                   const ObservationModel& observation, double pixel_sigmas) {
  allocate();
  observed_.upload(depth.data());
  const dt_model model = model_for(observation);
  std::vector<float> out(4 * poses.size()), packed;
  for (size_t first = 0; first < poses.size(); first += batch_) {
    const size_t n = std::min(batch_, poses.size() - first);
    upload_batch(poses.subspan(first, n), packed);
    kernels::launch({queue_, *visible_box_, compute::NdRange::linear(n * kBoxGroup, kBoxGroup)},
                    kernels::VisibleBoxArgs{.states = states_,
                                            .vertices = mesh_.vertices,
                                            .vertex_count = mesh_.vertex_count(),
                                            .observed = observed_,
                                            .camera = camera_,
                                            .model = model,
                                            .pixel_sigmas = static_cast<float>(pixel_sigmas),
                                            .boxes = boxes_});
    boxes_.download(std::span<float>(out.data() + 4 * first, 4 * n));
  }
  return out;
}

}  // namespace depthtrack
