#pragma once
// What tests inspect and set in a DeviceFilter, apart from its interface: its buffers downloaded for
// comparison with the reference filter, and its whole state replaced (for comparing backends from a
// common state). Each call downloads or uploads; nothing here is on a frame's path.
#include <vector>

#include "filter/device_filter.hpp"

namespace depthtrack {

class DeviceFilterProbe {
 public:
  explicit DeviceFilterProbe(DeviceFilter& filter) : f_(filter) {}

  // What the last update computed.
  std::vector<double> last_log_likelihoods() const;
  std::vector<int> last_parents() const;
  std::vector<model::ParticleState> particles() const;
  // The log weights the next frame adds to (0 after a resampling).
  std::vector<double> log_weights() const;
  // The particles as the last update weighed them (before it resampled).
  std::vector<model::ParticleState> weighed_particles() const;
  // Where the occlusion rows lie: the state window of the last frame (or of the start).
  const model::StateWindow& state_window() const { return f_.window_; }
  // How often an occlusion state buffer (probabilities or times, current or scratch) was allocated,
  // placeholders included: an automatic window's growth within its rows' room allocates nothing.
  size_t state_row_allocations() const { return f_.rows_.allocations(); }
  // The occlusion probabilities and times, particles x the state window's pixels, row-major from its
  // top-left corner (empty where the mode keeps none). A time is its frame's (0 for the start, and for a
  // pixel unseen for DT_TIME_RETIRE_AGE frames: cl/dt_time_index.h).
  std::vector<float> occlusion_state() const;
  std::vector<float> occlusion_times() const;
  // The atlas the last update weighed: particles x pixels depths, tile i = particle i. Where the
  // kernel renderer draws inside weigh the atlas is kept only after keep_atlas(true) (it costs a store
  // per pixel and particle and the atlas' memory), else this is an InputError.
  std::vector<float> last_atlas() const;
  void keep_atlas(bool keep);
  // Replaces the whole filter state. occlusion and occlusion_time hold particles x state window pixels
  // values (at state_window()), or are empty where the mode keeps none; each time must be 0 or the time
  // of a frame this filter has weighed since it was initialized.
  void set_state(const std::vector<model::ParticleState>& particles, const std::vector<float>& occlusion,
                 const std::vector<float>& occlusion_time, const std::vector<double>& log_weights);

 private:
  std::vector<model::ParticleState> current(std::vector<model::ParticleState> all) const;
  // Per-pixel rows downloaded in particle order: particle i's is row parents[i].
  template <typename T>
  std::vector<T> rows_by_parent(const compute::Buffer<T>& rows) const;

  DeviceFilter& f_;
};

}  // namespace depthtrack
