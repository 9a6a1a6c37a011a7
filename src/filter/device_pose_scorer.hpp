#pragma once
// Scores batches of poses on the compute device for global search: cl/rasterize.cl draws a batch
// into an atlas of its own, cl/score.cl sums each tile's likelihood terms with a fresh occlusion
// prior, and one download per batch brings the scores back. No filter state is read or written.
// Only as many poses as are asked for are drawn and scored (a last, partly filled batch launches
// fewer work-groups).
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <memory>

#include "atlas/atlas_layout.hpp"
#include "atlas/atlas_source.hpp"
#include "atlas/raster_inputs.hpp"
#include "compute/buffer.hpp"
#include "compute/program_cache.hpp"
#include "dt_params.h"
#include "model/pose_scorer.hpp"

namespace depthtrack {

// The two programs every scorer on one queue launches: taken from the device's program cache (when the
// tracker builds its own programs, not on the first search) and shared by the scorers made from them.
struct DevicePoseScorerPrograms {
  explicit DevicePoseScorerPrograms(compute::ProgramCache& programs);
  std::shared_ptr<compute::Program> rasterize, score, visible_box;
};

class DevicePoseScorer final : public PoseScorer {
 public:
  DevicePoseScorer(compute::Queue& queue, std::shared_ptr<const DevicePoseScorerPrograms> programs, const Mesh& mesh,
                   const Camera& camera, const TrackerConfig& config);
  ~DevicePoseScorer() override;

  std::vector<double> score(std::span<const Pose> poses, const DepthImage& depth,
                            const ObservationModel& model) override;
  std::vector<float> visible_boxes(std::span<const Pose> poses, const DepthImage& depth, const ObservationModel& model,
                                   double pixel_sigmas) override;
  // Poses drawn and scored per kernel launch at most (sized to fit device memory).
  size_t batch_size() const { return batch_; }

 private:
  compute::Queue& queue_;
  std::shared_ptr<const DevicePoseScorerPrograms> programs_;
  TrackerConfig config_;
  size_t pixels_, batch_;
  render::AtlasLayout layout_;
  MeshBuffers mesh_;
  dt_camera camera_;
  // The batch's buffers, made by the first search: a tracker that never loses its object needs none.
  void allocate();
  // The kernels' observation model: the tracker's with `observation` (its own or the search's tempered one).
  dt_model model_for(const ObservationModel& observation) const;
  // A batch's poses (at most batch_) packed as states into packed and uploaded.
  void upload_batch(std::span<const Pose> poses, std::vector<float>& packed);

  std::unique_ptr<compute::Kernel> rasterize_, score_, visible_box_;
  compute::Buffer<float> states_, atlas_, observed_, scores_, boxes_;  // allocated by allocate()
  compute::Buffer<unsigned> unused_boxes_;  // rasterize.cl's boxes, not written (whole tiles)
};

}  // namespace depthtrack
