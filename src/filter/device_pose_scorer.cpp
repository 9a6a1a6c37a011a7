#include "filter/device_pose_scorer.hpp"

#include <algorithm>
#include <string>

#include "compute/kernel_sources.hpp"
#include "core/pose_state.hpp"
#include "dt_state.h"
#include "filter/model_args.hpp"
#include "reference/pose_score.hpp"

namespace depthtrack {

namespace {
constexpr size_t kGroupSize = 128;  // work-items per pose in cl/score.cl, as in weigh
// Poses per launch: enough to fill a GPU at 80x60; on a CPU device a small batch wastes little
// on the last, partly filled one (its empty slots are still scored).
constexpr size_t kGpuBatch = 4096, kCpuBatch = 256;

// As many poses as a fifth of device memory holds (atlas tile and state each), at most the above.
size_t batch_for(const compute::Queue& queue, size_t pixels) {
  const size_t most = queue.info().is_gpu ? kGpuBatch : kCpuBatch;
  const double per_pose = 4.0 * (static_cast<double>(pixels) + DT_STATE_STRIDE + 1);
  const double memory = static_cast<double>(queue.info().global_memory);
  if (memory <= 0) return most;
  return std::clamp<size_t>(static_cast<size_t>(0.2 * memory / per_pose), 1, most);
}

TrackerConfig batch_config(const TrackerConfig& config, size_t batch) {
  TrackerConfig c = config;
  c.particles = static_cast<int>(batch);
  c.renderer = Renderer::Kernel;  // drawn where it is scored, whatever renderer the filter uses
  return c;
}
}  // namespace

DevicePoseScorer::DevicePoseScorer(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                   const TrackerConfig& config)
    : queue_(queue),
      config_(config),
      pixels_(static_cast<size_t>(camera.pixel_count())),
      batch_(batch_for(queue, pixels_)),
      atlas_source_(make_atlas_source(queue, mesh, camera, batch_config(config, batch_))),
      program_(
          queue.build("score.cl", compute::kernel_source("score.cl"), {"DT_GROUP_SIZE=" + std::to_string(kGroupSize)})),
      kernel_(program_->kernel("score")),
      states_(queue, batch_ * DT_STATE_STRIDE),
      atlas_(queue, atlas_source_->layout().floats()),
      observed_(queue, pixels_),
      scores_(queue, batch_) {}

DevicePoseScorer::~DevicePoseScorer() = default;

std::vector<double> DevicePoseScorer::score(std::span<const Pose> poses, const DepthImage& depth,
                                            const ObservationModel& observation) {
  observed_.upload(depth.data());
  TrackerConfig config = config_;
  config.observation = observation;
  const ModelArgs model = model_args(config);
  const float p = static_cast<float>(reference::fresh_occlusion(config_));
  std::vector<double> out;
  out.reserve(poses.size());
  std::vector<float> packed(batch_ * DT_STATE_STRIDE), scores(batch_);
  StepTimings unused;
  for (size_t first = 0; first < poses.size(); first += batch_) {
    const size_t n = std::min(batch_, poses.size() - first);
    // Unused slots of the last batch hold a pose behind the camera: clipped at once, nothing drawn.
    std::fill(packed.begin(), packed.end(), 0.0f);
    for (size_t i = 0; i < batch_; ++i) {
      float* s = packed.data() + i * DT_STATE_STRIDE;
      if (i < n) {
        write_pose(poses[first + i], s);
      } else {
        s[DT_TX + 2] = -1.0f;
        s[DT_QW] = 1.0f;
      }
    }
    states_.upload(packed);
    atlas_source_->draw(states_, atlas_, unused);
    compute::set_arg(*kernel_, 0, atlas_);
    compute::set_arg(*kernel_, 1, observed_);
    compute::set_arg(*kernel_, 2, scores_);
    kernel_->set_arg(3, static_cast<unsigned>(pixels_));
    kernel_->set_arg(4, model);
    kernel_->set_arg(5, p);
    kernel_->set_arg(6, atlas_source_->layout().kernel_args());
    queue_.launch(*kernel_, compute::NdRange::linear(batch_ * kGroupSize, kGroupSize));
    scores_.download(std::span<float>(scores.data(), batch_));
    out.insert(out.end(), scores.begin(), scores.begin() + static_cast<std::ptrdiff_t>(n));
  }
  return out;
}

}  // namespace depthtrack
