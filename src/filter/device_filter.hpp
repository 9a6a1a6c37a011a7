#pragma once
// The particle filter on a compute device (OpenCL or CUDA through src/compute): propagate, weigh,
// normalize and estimate, resample, all in kernels from cl/. The pose atlas it weighs comes from
// an AtlasSource: a compute kernel on this device, the GL renderer fed from and handing back to
// device memory, or the reference rasterizer on the host. Per frame only the depth image goes up
// and the estimate comes back.
#include <memory>
#include <optional>
#include <vector>

#include "atlas/atlas_source.hpp"
#include "atlas/raster_inputs.hpp"
#include "compute/buffer.hpp"
#include "compute/program_cache.hpp"
#include "filter/frame_time_table.hpp"
#include "model/filter_backend.hpp"
#include "model/particle.hpp"
#include "model/state_window.hpp"

namespace depthtrack {

// Device memory one particle's buffers take (the atlas unless it is drawn inside weigh, occlusion
// probabilities and 16-bit time indices twice for the state window's state_pixels (weigh reads one and
// writes the other; none given: the image's pixels), the state twice, weights; with GL pages, GL's colour and
// depth pages and its pose buffer): what the memory check refuses by and `depthtrack bench` reports.
double device_filter_bytes_per_particle(size_t pixels, OcclusionStorage mode, bool gl_pages, bool atlas = true,
                                        std::optional<size_t> state_pixels = std::nullopt);

// Whether the filter draws each particle's tile inside weigh (cl/render_weigh.cl), the tile in
// work-group memory: with the kernel renderer, where pixels' depths fit in the device's local memory
// per group, within the 48 KiB a CUDA block may declare statically (80x60 does; 160x120 does not).
// The one rule for the filter, its memory check and `depthtrack bench`.
bool renders_inside_weigh(Renderer renderer, size_t pixels, size_t local_memory);

// Tiles of the separate atlas the kernel renderer draws and weighs in turns: none where it draws inside
// weigh, else kernel_atlas_tiles (config.atlas_particles, one buffer of max_allocation bytes). The one rule
// for the filter, its memory check and `depthtrack bench`'s device_memory.
size_t kernel_renderer_atlas_tiles(const TrackerConfig& config, size_t pixels, size_t local_memory,
                                   size_t max_allocation);

// Up to this many particles a frame is bound by its launches (each costs the host 5-18 us on NVIDIA's
// OpenCL) more than by its kernels, so launches are folded together: render_weigh moves its particle
// itself (no propagate launch; its program is compiled with DT_PROPAGATE_INSIDE) and every resampling
// group scans the weights itself (resample_scanning, not prefix_sum + resample_particles; the groups
// repeat the scan, count^2 / 128 adds in all, which a GPU runs side by side). Larger clouds keep the
// separate kernels, and render_weigh its registers as before (the moving block costs it spills in
// NVRTC's allocation).
constexpr size_t kFusedLaunchParticles = 4096;

// Whether render_weigh moves the particles (propagate.cl's step, cl/dt_propagate.h) for this cloud.
bool propagates_inside_weigh(Renderer renderer, size_t pixels, size_t local_memory, size_t particles);

// render_weigh's work-group memory, decided once per filter: the pixels its tile holds (DT_TILE_PIXELS),
// the vertices whose projections it keeps (DT_SHARED_POINTS) and the groups a unit should hold
// (DT_RESIDENT_GROUPS).
struct RenderWeighLayout {
  size_t tile_pixels = 0, shared_points = 0, resident_groups = 0;
};

// The whole image's tile, or half its rows (rounded up) where that lets a unit hold at least two more
// groups or lets the mesh's projected points fit beside it: a pose's box is a small part of the image at
// the resolutions render_weigh runs at (ycbv-0000's objects at 80x60: 600-700 of 4,800 pixels), and the
// simplified mug's 1,600 points beside the whole image's tile let 5 groups onto an H100's unit, 7 with half.
// One group more was not worth it: the handset's frame at 1,000,000 particles took 20.4 ms on the H100 with
// the half tile (8 groups) against 18.2 with the whole (7). A taller box is then drawn
// and weighed in bands of rows (cl/render_weigh.cl); where the smaller tile gains less (the registers
// decide, or the device does not say what a unit holds) the tile stays whole: one band.
RenderWeighLayout render_weigh_layout(int width, int height, size_t vertex_count, const compute::DeviceInfo& device);

// How many vertices' projections render_weigh keeps in work-group memory beside its tile of tile_pixels
// (its DT_SHARED_POINTS): the mesh's vertex_count where they and the triangle list fit in the device's
// local memory (within CUDA's 48 KiB of static memory), else 0 (each triangle then projects its corners).
size_t render_weigh_shared_points(size_t tile_pixels, size_t vertex_count, size_t local_memory);

// How many render_weigh groups each compute unit should hold at once (its DT_RESIDENT_GROUPS), for its
// tile of tile_pixels and shared_points: compute::resident_groups of its work-group memory.
size_t render_weigh_resident_groups(size_t tile_pixels, size_t shared_points, const compute::DeviceInfo& device);

class DevicePoseScorer;
class WideSummary;
class DeviceRefiner;
struct DevicePoseScorerPrograms;

class DeviceFilter final : public FilterBackend {
 public:
  // On a device of its own.
  DeviceFilter(std::unique_ptr<compute::Queue> queue, const Mesh& mesh, const Camera& camera,
               const TrackerConfig& config);
  // On a device other filters may share: its queue, and its programs (built once for them all). With
  // config.renderer gl, `gl` is the Device's GL side (Device::gl_atlas; `device` is then gl->compute), whose
  // GL context the atlas is drawn in; without it the GL atlas makes a context of its own.
  DeviceFilter(std::shared_ptr<compute::DeviceContext> device, const Mesh& mesh, const Camera& camera,
               const TrackerConfig& config, const GlAtlasDevice* gl = nullptr);
  ~DeviceFilter() override;

  void initialize(const Pose& pose, const InitialSpread& spread) override;
  void initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) override;
  // Through a DevicePoseScorer made on first use (its atlas is separate from the filter's).
  std::vector<double> score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                  const ObservationModel& model) override;
  // A DevicePoseScorer on this filter's queue; the scoring programs are built on the first call
  // and shared by every scorer made after it.
  std::unique_ptr<PoseScorer> make_pose_scorer(const Mesh& mesh) override;
  Estimate update(const DepthImage& depth, double dt) override;
  // Enqueues the whole frame on this filter's queue (the depth's upload blocks on it alone);
  // collect() reads the estimate back, the frame's one wait.
  void enqueue_update(const DepthImage& depth, double dt) override;
  Estimate collect() override;
  std::string description() const override;
  std::pair<int, int> occlusion_window_size() const override { return {window_.width, window_.height}; }

  // What the last update computed, downloaded for comparison with the reference filter.
  std::vector<double> last_log_likelihoods() const;
  std::vector<int> last_parents() const;
  std::vector<model::ParticleState> particles() const;
  // Where the occlusion rows lie: the state window of the last frame (or of the start).
  const model::StateWindow& state_window() const { return window_; }
  // How often an occlusion state buffer (probabilities or times, current or scratch) was allocated,
  // placeholders included: an automatic window's growth within its rows' room allocates nothing.
  size_t state_row_allocations() const { return state_row_allocations_; }
  // The occlusion probabilities and times, particles x the state window's pixels, row-major from its
  // top-left corner (empty where the mode keeps none):
  // downloaded only when asked, for tests. A time is its frame's (0 for the start, and for a pixel
  // unseen for DT_TIME_RETIRE_AGE frames: cl/dt_time_index.h).
  std::vector<float> occlusion_state() const;
  std::vector<float> occlusion_times() const;
  // The atlas the last update weighed: particles x pixels depths, tile i = particle i. Where the
  // kernel renderer draws inside weigh the atlas is kept only after keep_atlas(true) (for tests; it
  // costs a store per pixel and particle and the atlas' memory), else this is an InputError.
  std::vector<float> last_atlas() const;
  void keep_atlas(bool keep);
  // The particles as the last update weighed them (before it resampled).
  std::vector<model::ParticleState> weighed_particles() const;
  // Replaces the whole filter state (for comparing backends from a common state). occlusion and
  // occlusion_time hold particles x state window pixels values (at state_window()), or are empty where the mode keeps
  // none; each time must be 0 or the time of a frame this filter has weighed since it was initialized.
  void set_state(const std::vector<model::ParticleState>& particles, const std::vector<float>& occlusion,
                 const std::vector<float>& occlusion_time, const std::vector<double>& log_weights);

 private:
  // A frame's launch, timed on the device when config.step_timings asks for it (else no event: null).
  template <class... Args>
  compute::EventPtr launch_step(compute::Kernel& kernel, const compute::NdRange& range, const Args&... args) {
    return compute::launch_timed_if(config_.step_timings, *queue_, kernel, range, args...);
  }
  struct Kernels;
  compute::EventPtr render_atlas(StepTimings& timings);
  // The per-particle device memory, checked before anything is allocated (an automatic window's
  // rows again at the start, when it is sized), and what the rows of `state_pixels` a particle take.
  size_t checked_particle_count() const;
  void check_state_memory(const model::StateWindow& window) const;
  double bytes_per_particle(size_t state_pixels) const;
  double atlas_bytes() const;        // the kernel renderer's atlas, apart from the particles' bytes
  size_t state_pixel_limit() const;  // computed once, into state_pixel_limit_
  void reserve_state_rows(compute::Buffer<float>& occlusion, compute::Buffer<uint16_t>& times,
                          const model::StateWindow& window);
  void upload_particles(const std::vector<model::ParticleState>& particles);
  std::vector<model::ParticleState> unpack(const compute::Buffer<float>& state) const;
  // Per-pixel rows downloaded in particle order: particle i's is row parents_[i].
  template <typename T>
  std::vector<T> rows_by_parent(const compute::Buffer<T>& rows) const;
  // Enqueues the resampling kernels, which resample only if the device decided to, and move the
  // children by the refinement's correction; their events. The weighed states stay in scratch_state_.
  std::vector<compute::EventPtr> resample();

  struct Pending;  // a frame between enqueue_update and collect: its clock and events
  void read_step_times(Pending& pending, StepTimings& timings) const;

  std::shared_ptr<compute::DeviceContext> device_;
  // A queue of this filter's own on device_ (so several filters' work overlaps), where the backend
  // offers one; queue_ is it, or else device_'s.
  std::unique_ptr<compute::Queue> own_queue_;
  compute::Queue* queue_;
  TrackerConfig config_;
  Camera camera_;
  Eigen::Vector3d centre_;
  size_t pixels_;
  // The state window (TrackerConfig::occlusion_window): where the occlusion rows lie (window_), and
  // where the next frame keeps them (next_window_: centred on the last estimate; an automatic window
  // sized from the object's extent).
  model::ObjectExtent extent_;
  model::StateWindow window_, next_window_;
  size_t count_;
  size_t state_pixel_limit_ = 0;  // the most pixels a window may grow to in the memory (0: no bound)
  size_t state_row_allocations_ = 0;
  size_t summary_group_ = 0;  // the one-group summary's work-items (none with the wide summary)
  std::unique_ptr<AtlasSource> atlas_source_;
  std::unique_ptr<Kernels> kernels_;
  std::unique_ptr<PoseScorer> scorer_;
  std::shared_ptr<const DevicePoseScorerPrograms> scoring_programs_;
  Mesh mesh_;  // kept for score_poses' scorer, made only when it is first called
  compute::Buffer<float> state_, scratch_state_, log_weight_, log_likelihood_, weights_, cumulative_, estimate_;
  compute::Buffer<unsigned> parents_;
  // Where the frame's estimate arrives (Queue::read_enqueued, before the resampling): the filter's own,
  // so that it outlives any frame left uncollected.
  std::vector<float> estimate_host_;
  compute::Buffer<float> atlas_, observed_;
  compute::Buffer<unsigned> unused_boxes_;  // weigh's boxes argument where the atlas source keeps none
  compute::Buffer<float> no_correction_;    // resample_particles' correction argument without the refinement
  // The kernel renderer's rasterization inside weigh (renders_inside_weigh), drawing the kernel atlas
  // source's mesh.
  std::unique_ptr<compute::Kernel> render_weigh_;
  const MeshBuffers* render_weigh_mesh_ = nullptr;
  bool propagates_in_weigh_ = false;  // propagates_inside_weigh: no propagate launch
  bool fit_summarizes_ = false;       // the one-launch fit summarizes in its own launch: no summarize launch
  bool keep_atlas_ = false;
  // Per-pixel occlusion state, double-buffered: weigh reads particle i's row parents_[i] of one and
  // writes row i of the other (cl/weigh.cl), so resampling copies no rows; parents_ is the identity
  // after initialize and set_state.
  compute::Buffer<float> occlusion_, scratch_occlusion_;
  // Per-pixel time: each pixel's last frame as an index into frame_times_ (cl/dt_time_index.h).
  compute::Buffer<uint16_t> occlusion_time_, scratch_occlusion_time_;
  std::unique_ptr<FrameTimeTable> frame_times_;
  std::unique_ptr<DeviceRefiner> refiner_;  // when config.refine.enabled
  std::unique_ptr<WideSummary> wide_;       // the summary over many groups, for large clouds
  std::unique_ptr<Pending> pending_;
  bool last_resampled_ = false;
  bool weighed_in_scratch_ = false;  // the last update left the weighed states in scratch_state_
  unsigned frame_ = 0;
  double time_ = 0;
};

}  // namespace depthtrack
