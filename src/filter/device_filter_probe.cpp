#include "filter/device_filter_probe.hpp"

#include <algorithm>
#include <depthtrack/error.hpp>
#include <numeric>
#include <string>

#include "model/particle_packing.hpp"

namespace depthtrack {

// The buffers hold the most particles; the current count's are the first.
std::vector<model::ParticleState> DeviceFilterProbe::current(std::vector<model::ParticleState> all) const {
  all.resize(f_.plan_.particles);
  return all;
}

std::vector<double> DeviceFilterProbe::last_log_likelihoods() const {
  const std::vector<float> ll = f_.buffers_.log_likelihood.download();
  return std::vector<double>(ll.begin(), ll.begin() + static_cast<std::ptrdiff_t>(f_.plan_.particles));
}

std::vector<double> DeviceFilterProbe::log_weights() const {
  const std::vector<float> lw = f_.buffers_.log_weight.download();
  return std::vector<double>(lw.begin(), lw.begin() + static_cast<std::ptrdiff_t>(f_.plan_.particles));
}

std::vector<int> DeviceFilterProbe::last_parents() const {
  std::vector<int> parents(f_.plan_.particles);
  if (!f_.last_resampled_) {
    std::iota(parents.begin(), parents.end(), 0);
    return parents;
  }
  const std::vector<unsigned> p = f_.buffers_.parents.download();
  for (size_t i = 0; i < parents.size(); ++i) parents[i] = static_cast<int>(p[i]);
  return parents;
}

std::vector<model::ParticleState> DeviceFilterProbe::particles() const {
  return current(unpack_particles(f_.buffers_.state.download()));
}

// Resampling gathers into the scratch buffer and swaps, so the weighed states are left there.
std::vector<model::ParticleState> DeviceFilterProbe::weighed_particles() const {
  return current(unpack_particles((f_.weighed_in_scratch_ ? f_.buffers_.scratch_state : f_.buffers_.state).download()));
}

// Particle i's row is parents[i] of the buffer (cl/weigh.cl folds the gather into the next frame).
template <typename T>
std::vector<T> DeviceFilterProbe::rows_by_parent(const compute::Buffer<T>& rows) const {
  const std::vector<T> all = rows.download();
  const std::vector<unsigned> parents = f_.buffers_.parents.download();
  const size_t row = f_.window_.pixels(), count = f_.plan_.particles;
  std::vector<T> gathered(count * row);
  for (size_t i = 0; i < count; ++i)
    std::copy_n(all.begin() + static_cast<std::ptrdiff_t>(parents[i] * row), row,
                gathered.begin() + static_cast<std::ptrdiff_t>(i * row));
  return gathered;
}

std::vector<float> DeviceFilterProbe::occlusion_state() const {
  return f_.config_.occlusion_storage == OcclusionStorage::Off ? std::vector<float>{}
                                                               : rows_by_parent(f_.rows_.occlusion);
}

std::vector<float> DeviceFilterProbe::occlusion_times() const {
  return f_.config_.occlusion_storage == OcclusionStorage::PerPixelTime
             ? f_.frame_times_->times(rows_by_parent(f_.rows_.time))
             : std::vector<float>{};
}

std::vector<float> DeviceFilterProbe::last_atlas() const {
  const AtlasSource& source = *f_.atlas_source_;
  const size_t count = f_.plan_.particles, pixels = f_.plan_.pixels;
  const bool inside = f_.plan_.weigh == WeighStep::RenderWeigh;
  if (inside && !f_.keep_atlas_)
    throw InputError("device filter: the atlas is drawn inside weigh and not kept (keep_atlas(true) keeps it)");
  if (source.layout().tiles() < count)
    throw InputError("device filter: the atlas holds " + std::to_string(source.layout().tiles()) +
                     " tiles, drawn in turns: only the last turn's are left");
  std::vector<float> tiles = source.layout().tiles_in_order(f_.buffers_.atlas.download(), count);
  if (const compute::Buffer<unsigned>* boxes = source.tile_boxes()) {
    // Drawn only inside each pose's box: the rest of its tile is stale, and empty to weigh.
    const std::vector<unsigned> b = boxes->download();
    const size_t width = static_cast<size_t>(f_.camera_.width);
    for (size_t i = 0; i < count; ++i)
      for (size_t k = 0; k < pixels; ++k) {
        const unsigned u = static_cast<unsigned>(k % width), v = static_cast<unsigned>(k / width);
        if (u - b[4 * i] >= b[4 * i + 2] || v - b[4 * i + 1] >= b[4 * i + 3]) tiles[i * pixels + k] = 0.0f;
      }
  }
  return tiles;
}

void DeviceFilterProbe::keep_atlas(bool keep) {
  const AtlasSource& source = *f_.atlas_source_;
  const bool inside = f_.plan_.weigh == WeighStep::RenderWeigh;
  // render_weigh writes particle i's tile at i: the layout must hold them all.
  if (keep && inside && source.layout().tiles() < f_.plan_.particles)
    throw InputError("device filter: an atlas of " + std::to_string(source.layout().tiles()) + " tiles cannot keep " +
                     std::to_string(f_.plan_.particles) + " particles' (TrackerConfig::atlas_particles)");
  f_.keep_atlas_ = keep;
  if (inside) f_.buffers_.atlas = compute::Buffer<float>(*f_.queue_, keep ? source.layout().floats() : 1);
}

void DeviceFilterProbe::set_state(const std::vector<model::ParticleState>& particles,
                                  const std::vector<float>& occlusion, const std::vector<float>& occlusion_time,
                                  const std::vector<double>& log_weights) {
  const size_t count = f_.plan_.particles;
  if (particles.size() != count || log_weights.size() != count)
    throw InputError("set_state: expected " + std::to_string(count) + " particles");
  const size_t rows = count * f_.window_.pixels();
  if ((!occlusion.empty() && occlusion.size() != rows) || (!occlusion_time.empty() && occlusion_time.size() != rows))
    throw InputError("set_state: expected " + std::to_string(rows) + " occlusion values (particles x state window)");
  f_.buffers_.state.upload(pack_particles(particles));
  f_.buffers_.log_weight.upload(std::vector<float>(log_weights.begin(), log_weights.end()));
  if (!occlusion.empty()) f_.rows_.occlusion.upload(occlusion);
  if (!occlusion_time.empty()) f_.rows_.time.upload(f_.frame_times_->indices(occlusion_time));
  f_.steps_->identity_parents();  // in queue order before the next frame's weigh
  f_.rows_particles_ = count;
}

}  // namespace depthtrack
