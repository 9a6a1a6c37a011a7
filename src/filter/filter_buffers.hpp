#pragma once
// The device filter's per-particle buffers besides the occlusion rows (filter/state_rows.hpp), sized by
// the plan of the most particles (TrackerConfig::particles) once: a smaller count uses their first rows.
#include <cstddef>
#include <vector>

#include "compute/buffer.hpp"
#include "dt_state.h"
#include "filter/frame_plan.hpp"

namespace depthtrack {

struct FilterBuffers {
  // atlas_floats: the atlas source's layout (AtlasSource::layout().floats()); refine: whether the fit
  // runs (else resample_particles' correction is a placeholder, never read).
  FilterBuffers(compute::Queue& queue, const FramePlan& plan, size_t atlas_floats, bool refine)
      : state(queue, plan.particles * DT_STATE_STRIDE),
        scratch_state(queue, plan.particles * DT_STATE_STRIDE),
        log_weight(queue, plan.particles),
        log_likelihood(queue, plan.particles),
        weights(queue, plan.particles),
        estimate(queue, DT_EST_SIZE),
        parents(queue, plan.particles),
        choice(queue, plan.particles),
        // Drawn inside weigh, the atlas is stored only when asked for (DeviceFilterProbe::keep_atlas).
        atlas(queue, plan.needs_atlas() ? atlas_floats : 1),
        observed(queue, plan.pixels),
        estimate_host(DT_EST_SIZE) {
    if (plan.needs_cumulative()) cumulative = compute::Buffer<float>(queue, 2 * plan.particles);  // float-float
    if (!refine) no_correction = compute::Buffer<float>(queue, 6);
  }

  compute::Buffer<float> state, scratch_state, log_weight, log_likelihood, weights, cumulative, estimate;
  // Particle i's parent in the last resampling (the identity after initialize and set_state): the next
  // frame's weigh reads particle i's occlusion rows from row parents[i].
  compute::Buffer<unsigned> parents;
  // A new count's children's particles (DeviceFilter::set_particle_count), as many as the most particles.
  compute::Buffer<unsigned> choice;
  compute::Buffer<float> atlas, observed;
  compute::Buffer<unsigned> unused_boxes;  // weigh's boxes argument where the atlas source keeps none
  compute::Buffer<float> no_correction;    // the resampling's correction argument without the refinement
  // Where the frame's estimate arrives (Queue::read_enqueued, before the resampling): the filter's own,
  // so that it outlives any frame left uncollected.
  std::vector<float> estimate_host;
};

}  // namespace depthtrack
