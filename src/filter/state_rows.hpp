#pragma once
// The device filter's per-pixel occlusion state and the memory it may take: the probabilities and
// 16-bit time indices, particles x the state window's pixels each, double-buffered (weigh reads
// particle i's row parents[i] of the current buffers and writes row i of the scratch ones, which then
// become current: resampling copies no rows). Also the memory check the filter refuses a cloud by.
#include <cstddef>
#include <cstdint>
#include <depthtrack/camera.hpp>
#include <depthtrack/tracker_config.hpp>

#include "compute/buffer.hpp"
#include "filter/frame_plan.hpp"
#include "model/state_window.hpp"

namespace depthtrack {

class StateRows {
 public:
  // Checks config's particles against the device's memory with window's rows (an automatic window has
  // none before the start; check() again once it is sized). Allocates nothing.
  StateRows(compute::Queue& queue, const TrackerConfig& config, const Camera& camera, const FramePlan& plan,
            const model::StateWindow& window);

  // InputError naming what fits where the cloud with window's rows does not fit in 90 % of the memory.
  void check(const model::StateWindow& window) const;
  // Rows for window in the current or the scratch pair, reallocated only when they hold fewer.
  void reserve_current(const model::StateWindow& window) { reserve(occlusion, time, window); }
  void reserve_scratch(const model::StateWindow& window) { reserve(scratch_occlusion, scratch_time, window); }
  // After weigh wrote the scratch pair: it becomes the current one.
  void swap();

  // How often a state buffer (probabilities or times, current or scratch) was allocated, placeholders
  // included: an automatic window's growth within its rows' room allocates nothing.
  size_t allocations() const { return allocations_; }
  // The most pixels a window may grow to in the memory (0: no bound).
  size_t pixel_limit() const { return pixel_limit_; }

  // A mode that keeps no such state has a placeholder (one element; two 16-bit ones): kernels take both.
  compute::Buffer<float> occlusion, scratch_occlusion;
  compute::Buffer<uint16_t> time, scratch_time;  // frame indices (cl/dt_time_index.h)

 private:
  double bytes_per_particle(size_t state_pixels) const;
  double atlas_bytes() const;  // the kernel renderer's atlas, apart from the particles' bytes
  size_t compute_pixel_limit() const;
  void reserve(compute::Buffer<float>& probabilities, compute::Buffer<uint16_t>& times,
               const model::StateWindow& window);

  compute::Queue& queue_;
  const TrackerConfig& config_;
  Camera camera_;
  size_t count_, pixels_, atlas_tiles_;
  size_t pixel_limit_ = 0, allocations_ = 0;
};

}  // namespace depthtrack
