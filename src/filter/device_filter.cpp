#include "filter/device_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <depthtrack/error.hpp>
#include <numeric>
#include <sstream>

#include "compute/program_cache.hpp"
#include "compute/resident_groups.hpp"
#include "core/stopwatch.hpp"
#include "dt_draw_list.h"
#include "dt_state.h"
#include "dt_summary.h"
#include "dt_time_index.h"
#include "filter/device_pose_scorer.hpp"
#include "filter/device_refiner.hpp"
#include "filter/wide_summary.hpp"
#include "model/kernel_params.hpp"
#include "model/particle_packing.hpp"
#include "model/fit_noise.hpp"
#include "philox.h"

namespace depthtrack {

namespace {
constexpr size_t kGroupSize = 128;   // work-items per group in weigh, summarize and the per-pixel fills
constexpr size_t kLinearGroup = 64;  // work-items per group in the per-particle kernels

// A run of launches' device time from its first event to its last, the gaps between them included
// (the launches between are untimed); the events' own times added where the backend has no common clock.
double device_span_ms(const std::vector<compute::EventPtr>& events) {
  if (events.size() > 1)
    if (const auto span = events.back()->elapsed_since_ms(*events.front())) return *span;
  double ms = 0;
  for (const auto& event : events) ms += event->elapsed_ms();
  return ms;
}

size_t round_up(size_t n, size_t multiple) {
  return (n + multiple - 1) / multiple * multiple;
}

// The one-group summary's work-items. Its passes over the particles are chains of loads, one per
// particle a work-item takes; on a GPU a bigger group makes each chain shorter. A CPU runs a group's
// work-items in turn, so the filter's size stays there.
constexpr size_t kGpuSummaryGroup = 512;
size_t summary_group_size(const compute::DeviceInfo& device) {
  if (!device.is_gpu) return kGroupSize;
  size_t size = kGroupSize;
  while (size * 2 <= std::min(kGpuSummaryGroup, device.max_work_group_size)) size *= 2;
  return size;
}
}  // namespace

double device_filter_bytes_per_particle(size_t pixels, OcclusionStorage mode, bool gl_pages, bool atlas,
                                        std::optional<size_t> state_pixels) {
  const bool occlusion = mode != OcclusionStorage::Off, times = mode == OcclusionStorage::PerPixelTime;
  const double image_floats = (atlas ? 1 : 0) + (gl_pages ? 2 : 0);
  const double state_floats = (occlusion ? 2 : 0) + (times ? 1 : 0);  // times: 2 x 16 bits
  const double kept = static_cast<double>(state_pixels.value_or(pixels));
  return 4.0 * (static_cast<double>(pixels) * image_floats + kept * state_floats +
                (2 + (gl_pages ? 1 : 0)) * DT_STATE_STRIDE + 6);
}

namespace {
constexpr size_t kStaticLocalLimit = 48 * 1024;  // CUDA's for a block's static shared memory

// The tile, and the pose box's reduction, which the group sum reuses.
size_t render_weigh_local_bytes(size_t pixels) {
  return pixels * sizeof(float) + pose_box_scratch_bytes(kGroupSize);
}
}  // namespace

bool renders_inside_weigh(Renderer renderer, size_t pixels, size_t local_memory) {
  return renderer == Renderer::Kernel && render_weigh_local_bytes(pixels) <= std::min(local_memory, kStaticLocalLimit);
}

size_t kernel_renderer_atlas_tiles(const TrackerConfig& config, size_t pixels, size_t local_memory,
                                   size_t max_allocation) {
  if (renders_inside_weigh(Renderer::Kernel, pixels, local_memory)) return 0;
  return kernel_atlas_tiles(static_cast<size_t>(config.particles), pixels, config.atlas_particles, max_allocation);
}

bool propagates_inside_weigh(Renderer renderer, size_t pixels, size_t local_memory, size_t particles) {
  return particles <= kFusedLaunchParticles && renders_inside_weigh(renderer, pixels, local_memory);
}

namespace {
// render_weigh's work-group memory with shared_points' projections kept: the tile and reduction, the
// points, the triangle list (cl/dt_draw_list.h) with each one's first row, and its tally.
size_t render_weigh_group_bytes(size_t tile_pixels, size_t shared_points) {
  static_assert((uint64_t{DT_DRAW_LIST} << DT_ROW_BITS) < (uint64_t{1} << 32), "a full list's tally overflows 32 bits");
  return render_weigh_local_bytes(tile_pixels) +
         (shared_points > 0 ? shared_points * 2 * sizeof(float) + (2 * DT_DRAW_LIST + 1) * sizeof(unsigned) : 0);
}
}  // namespace

size_t render_weigh_shared_points(size_t tile_pixels, size_t vertex_count, size_t local_memory) {
  const size_t needed = render_weigh_group_bytes(tile_pixels, vertex_count);
  return vertex_count > 0 && needed <= std::min(local_memory, kStaticLocalLimit) ? vertex_count : 0;
}

size_t render_weigh_resident_groups(size_t tile_pixels, size_t shared_points, const compute::DeviceInfo& device) {
  return compute::resident_groups(render_weigh_group_bytes(tile_pixels, shared_points), kGroupSize, device);
}

RenderWeighLayout render_weigh_layout(int width, int height, size_t vertex_count, const compute::DeviceInfo& device) {
  auto layout = [&](size_t tile) {
    RenderWeighLayout l;
    l.tile_pixels = tile;
    l.shared_points = render_weigh_shared_points(tile, vertex_count, device.local_memory);
    l.resident_groups = render_weigh_resident_groups(tile, l.shared_points, device);
    return l;
  };
  const RenderWeighLayout whole = layout(static_cast<size_t>(width) * static_cast<size_t>(height)),
                          half = layout(static_cast<size_t>(width) * static_cast<size_t>((height + 1) / 2));
  return half.resident_groups >= whole.resident_groups + 2 || half.shared_points > whole.shared_points ? half : whole;
}

struct DeviceFilter::Kernels {
  std::shared_ptr<compute::Program> propagate_program, weigh_program, summarize_program, resample_program,
      initialize_program;
  std::unique_ptr<compute::Kernel> propagate, weigh, summarize, prefix_sum, resample_particles, resample_scanning,
      identity_parents, fill, initialize_particles, fill_per_particle, fill_time_indices, retire_time_indices;
};

DeviceFilter::DeviceFilter(std::unique_ptr<compute::Queue> queue, const Mesh& mesh, const Camera& camera,
                           const TrackerConfig& config)
    : DeviceFilter(std::make_shared<compute::DeviceContext>(std::move(queue)), mesh, camera, config) {}

DeviceFilter::DeviceFilter(std::shared_ptr<compute::DeviceContext> device, const Mesh& mesh, const Camera& camera,
                           const TrackerConfig& config, const GlAtlasDevice* gl)
    : device_(std::move(device)),
      own_queue_(device_->make_queue()),
      queue_(own_queue_ ? own_queue_.get() : device_->queue.get()),
      config_(config),
      camera_(camera),
      centre_(mesh.centre().cast<double>()),
      pixels_(static_cast<size_t>(camera.pixel_count())),
      extent_(model::object_extent(mesh)),
      window_(model::state_window_size(config, camera)),
      next_window_(window_),
      count_(checked_particle_count()),
      atlas_source_(make_atlas_source(*queue_, device_->programs, mesh, camera, config, gl)),
      mesh_(mesh) {
  // A fixed window of the whole image: weigh then indexes the state by pixel (cl/dt_window.h).
  const bool whole_image = !config.occlusion_window.is_automatic() && window_.pixels() == pixels_;
  const std::vector<std::string> defines = {"DT_GROUP_SIZE=" + std::to_string(kGroupSize),
                                            model::occlusion_definition(config.occlusion_storage),
                                            whole_image ? "DT_WHOLE_IMAGE_STATE=1" : "DT_WHOLE_IMAGE_STATE=0"};
  kernels_ = std::make_unique<Kernels>();
  Kernels& k = *kernels_;
  k.resample_program = device_->programs.program("resample.cl", defines);
  // The summary and prefix sum: one group for a few thousand particles (the summary's kernel below),
  // many for large clouds; a small cloud's resampling groups scan the weights themselves.
  if (count_ >= kWideSummaryParticles)
    wide_ = std::make_unique<WideSummary>(*queue_, device_->programs,
                                          model::occlusion_definition(config.occlusion_storage), count_);
  else if (count_ > kFusedLaunchParticles)
    k.prefix_sum = k.resample_program->kernel("prefix_sum");
  if (count_ <= kFusedLaunchParticles)
    k.resample_scanning = k.resample_program->kernel("resample_scanning");
  else
    k.resample_particles = k.resample_program->kernel("resample_particles");
  k.identity_parents = k.resample_program->kernel("identity_parents");
  k.fill = k.resample_program->kernel("fill");
  k.initialize_program = device_->programs.program("initialize.cl", defines);
  k.initialize_particles = k.initialize_program->kernel("initialize_particles");
  k.fill_per_particle = k.initialize_program->kernel("fill_per_particle");
  if (config.occlusion_storage == OcclusionStorage::PerPixelTime) {  // cl/time_index.cl, in resample.cl's program
    k.fill_time_indices = k.resample_program->kernel("fill_time_indices");
    k.retire_time_indices = k.resample_program->kernel("retire_time_indices");
  }

  compute::Queue& q = *queue_;
  state_ = compute::Buffer<float>(q, count_ * DT_STATE_STRIDE);
  scratch_state_ = compute::Buffer<float>(q, count_ * DT_STATE_STRIDE);
  log_weight_ = compute::Buffer<float>(q, count_);
  log_likelihood_ = compute::Buffer<float>(q, count_);
  weights_ = compute::Buffer<float>(q, count_);
  if (!kernels_->resample_scanning) cumulative_ = compute::Buffer<float>(q, 2 * count_);  // float-float pairs
  parents_ = compute::Buffer<unsigned>(q, count_);
  estimate_ = compute::Buffer<float>(q, DT_EST_SIZE);
  estimate_host_.resize(DT_EST_SIZE);
  if (renders_inside_weigh(config.renderer, pixels_, q.info().local_memory) && atlas_source_->device_mesh()) {
    propagates_in_weigh_ = propagates_inside_weigh(config.renderer, pixels_, q.info().local_memory, count_);
    const RenderWeighLayout layout =
        render_weigh_layout(camera_.width, camera_.height, atlas_source_->device_mesh()->vertex_count(), q.info());
    render_weigh_ =
        device_->programs
            .program("render_weigh.cl",
                     {defines[0], defines[1], defines[2], "DT_TILE_PIXELS=" + std::to_string(layout.tile_pixels),
                      "DT_SHARED_POINTS=" + std::to_string(layout.shared_points),
                      "DT_PROPAGATE_INSIDE=" + std::string(propagates_in_weigh_ ? "1" : "0"),
                      "DT_RESIDENT_GROUPS=" + std::to_string(layout.resident_groups)})
            ->kernel("render_weigh");
    render_weigh_mesh_ = atlas_source_->device_mesh();
  } else {  // the atlas drawn by its source (only each pose's box where it can), then weighed
    k.weigh_program = device_->programs.program("weigh.cl", defines);
    k.weigh = k.weigh_program->kernel("weigh");
    atlas_source_->draw_boxed();
    if (!atlas_source_->tile_boxes()) unused_boxes_ = compute::Buffer<unsigned>(q, 4);  // whole tiles
  }
  // Drawn inside weigh, the atlas is stored only when asked for (keep_atlas).
  atlas_ = compute::Buffer<float>(q, render_weigh_ ? 1 : atlas_source_->layout().floats());
  observed_ = compute::Buffer<float>(q, pixels_);
  // An automatic window's rows are allocated once the start sizes it.
  state_pixel_limit_ = state_pixel_limit();
  reserve_state_rows(occlusion_, occlusion_time_, window_);
  reserve_state_rows(scratch_occlusion_, scratch_occlusion_time_, window_);
  frame_times_ = std::make_unique<FrameTimeTable>(q);
  if (config.refine.enabled)
    refiner_ = std::make_unique<DeviceRefiner>(q, device_->programs, mesh, camera, config,
                                               model::occlusion_definition(config.occlusion_storage));
  else
    no_correction_ = compute::Buffer<float>(q, 6);  // never read: resample_particles' shift is off
  // Only the kernels the frame launches are built (a CPU device compiles each for a while).
  if (!propagates_in_weigh_) {
    k.propagate_program = device_->programs.program("propagate.cl", defines);
    k.propagate = k.propagate_program->kernel("propagate");
  }
  // The one-launch fit summarizes in its own group first (one launch for both); a wide summary stays apart.
  fit_summarizes_ = refiner_ && !wide_ && refiner_->summarizes_first();
  if (!wide_ && !fit_summarizes_) {
    summary_group_ = summary_group_size(q.info());
    std::vector<std::string> summary_defines = defines;
    summary_defines.front() = "DT_GROUP_SIZE=" + std::to_string(summary_group_);
    k.summarize_program = device_->programs.program("summarize.cl", summary_defines);
    k.summarize = k.summarize_program->kernel("summarize");
  }
}

struct DeviceFilter::Pending {
  Stopwatch clock;
  StepTimings timings;  // the atlas source's host part
  compute::EventPtr propagated;
  std::vector<compute::EventPtr> rendered, weighed;  // one each per turn of the atlas' tiles
  std::vector<compute::EventPtr> summarized, refined, resampling;
};

DeviceFilter::~DeviceFilter() {
  // A shared queue may outlive this filter: a read of an uncollected (or failed) frame's estimate
  // lands before estimate_host_ goes.
  try {
    queue_->wait_enqueued_reads();
  } catch (...) {  // a device error at teardown has nowhere to go
  }
}

double DeviceFilter::bytes_per_particle(size_t state_pixels) const {
  // GL's pages sit on the same GPU; the kernel renderer's atlas is counted apart (atlas_bytes).
  return device_filter_bytes_per_particle(pixels_, config_.occlusion_storage,
                                          config_.renderer == Renderer::Gl && queue_->info().is_gpu,
                                          config_.renderer != Renderer::Kernel, state_pixels);
}

// The kernel renderer's atlas (kernel_renderer_atlas_tiles); the other renderers' is counted per particle.
double DeviceFilter::atlas_bytes() const {
  if (config_.renderer != Renderer::Kernel) return 0;
  const auto& info = queue_->info();
  return static_cast<double>(kernel_renderer_atlas_tiles(config_, pixels_, info.local_memory, info.max_allocation)) *
         static_cast<double>(pixels_) * sizeof(float);
}

// An automatic window has no size before the start: checked without its rows here, and again by
// check_state_memory once the start sizes it.
size_t DeviceFilter::checked_particle_count() const {
  check_state_memory(window_);
  return static_cast<size_t>(config_.particles);
}

void DeviceFilter::check_state_memory(const model::StateWindow& window) const {
  const double per_particle = bytes_per_particle(window.pixels()), atlas = atlas_bytes();
  const double needed = per_particle * static_cast<double>(config_.particles) + atlas;
  const auto& info = queue_->info();
  if (info.global_memory > 0 && needed > 0.9 * static_cast<double>(info.global_memory)) {
    std::ostringstream m;
    m.precision(3);
    m << model::particles_and_window(config_, camera_, window) << " need " << needed / (1 << 30)
      << " GiB of device memory but " << info.name << " has " << static_cast<double>(info.global_memory) / (1 << 30)
      << " GiB; at most about "
      << static_cast<long long>(std::max(0.0, 0.9 * static_cast<double>(info.global_memory) - atlas) / per_particle)
      << " particles fit" << (atlas > 0 ? " beside the atlas (TrackerConfig::atlas_particles makes it smaller)" : "");
    throw InputError(m.str());
  }
}

// The most state pixels a particle's rows may grow to in 90 % of the device's memory (0: unknown).
size_t DeviceFilter::state_pixel_limit() const {
  const double memory = static_cast<double>(queue_->info().global_memory);
  const double per_pixel = bytes_per_particle(1) - bytes_per_particle(0);
  if (!(memory > 0) || per_pixel == 0) return 0;
  const double share = (0.9 * memory - atlas_bytes()) / static_cast<double>(count_) - bytes_per_particle(0);
  return share < per_pixel ? 1 : static_cast<size_t>(share / per_pixel);
}

// Rows for `window` in a pair of state buffers (probabilities, times), reallocated only when they hold
// fewer: an automatic window's rows are sized at the start and grow with it. Kernels always take both
// buffers, so a mode that keeps no such state gets the placeholder (one element; two 16-bit ones).
void DeviceFilter::reserve_state_rows(compute::Buffer<float>& occlusion, compute::Buffer<uint16_t>& times,
                                      const model::StateWindow& window) {
  const size_t kept = count_ * window.pixels();
  // An automatic window grows by a pixel or two a frame while the estimate settles or the object
  // nears, so its rows take half as much again (within the memory's bound), at the start as when
  // outgrown, rather than being reallocated every few frames: a reallocation's free waits for the
  // device, that is for every object's work queued on it, and changes the frame's graph. A fixed
  // window never grows: its rows are what it needs.
  const auto rows = [&](size_t placeholder) {
    if (!config_.occlusion_window.is_automatic()) return std::max(kept, placeholder);
    const size_t roomy = kept + kept / 2, limit = state_pixel_limit_ * count_;
    return std::max({kept, placeholder, limit > 0 ? std::min(roomy, limit) : roomy});
  };
  const bool probabilities = config_.occlusion_storage != OcclusionStorage::Off;
  const bool indices = config_.occlusion_storage == OcclusionStorage::PerPixelTime;
  if (probabilities ? occlusion.size() < std::max<size_t>(kept, 1) : occlusion.size() < 1) {
    occlusion = compute::Buffer<float>(*queue_, probabilities ? rows(1) : 1);
    ++state_row_allocations_;
  }
  if (indices ? times.size() < std::max<size_t>(kept, 2) : times.size() < 2) {
    times = compute::Buffer<uint16_t>(*queue_, indices ? rows(2) : 2);
    ++state_row_allocations_;
  }
}

std::string DeviceFilter::description() const {
  const auto& info = queue_->info();
  return info.selector + " " + info.name + " (" + info.platform + "); atlas: " + atlas_source_->description() +
         (render_weigh_ ? "; drawn inside weigh (tiles in work-group memory)" : "");
}

void DeviceFilter::upload_particles(const std::vector<model::ParticleState>& particles) {
  state_.upload(pack_particles(particles));
}

// Drawn and filled on the device (cl/initialize.cl) with the reference's draws: start-up holds no
// host copy of the particles or of their particles x pixels occlusion state.
void DeviceFilter::initialize(const Pose& pose, const InitialSpread& spread) {
  initialize_modes(std::span<const Pose>(&pose, 1), spread);
}

std::vector<double> DeviceFilter::score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                              const ObservationModel& model) {
  if (!scorer_) scorer_ = make_pose_scorer(mesh_);
  return scorer_->score(poses, depth, model);
}

std::unique_ptr<PoseScorer> DeviceFilter::make_pose_scorer(const Mesh& mesh) {
  if (!scoring_programs_) scoring_programs_ = std::make_shared<const DevicePoseScorerPrograms>(device_->programs);
  return std::make_unique<DevicePoseScorer>(*queue_, scoring_programs_, mesh, camera_, config_);
}

// Drawn on the device (cl/initialize.cl) with the reference's draws, particle i around mode
// i % modes: no host copy of particles x pixels values at start-up.
void DeviceFilter::initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) {
  if (modes.empty()) throw InputError("initialize_modes: no pose to start from");
  Kernels& k = *kernels_;
  std::vector<float> mode_values;
  mode_values.reserve(modes.size() * 7);
  for (const Pose& m : modes) {
    const Eigen::Quaterniond& q = m.rotation;
    for (double v : {m.translation.x(), m.translation.y(), m.translation.z(), q.w(), q.x(), q.y(), q.z()})
      mode_values.push_back(static_cast<float>(v));
  }
  // An automatic window is sized here: its rows are checked and allocated (a fixed one's already were).
  window_ = next_window_ = model::start_state_window(config_, extent_, modes.front(), camera_);
  check_state_memory(window_);
  reserve_state_rows(occlusion_, occlusion_time_, window_);
  compute::Buffer<float> mode_buffer(*queue_, mode_values.size());
  mode_buffer.upload(mode_values);
  const auto linear = compute::NdRange::linear(round_up(count_, kLinearGroup), kLinearGroup);
  const unsigned count = static_cast<unsigned>(count_);
  queue_->launch(*k.initialize_particles, linear, state_, count, static_cast<unsigned>(config_.seed & 0xffffffffu),
                 static_cast<unsigned>(config_.seed >> 32), mode_buffer,
                 model::initial_params(spread, centre_, modes.size()));
  queue_->launch(*k.fill, linear, log_weight_, count, 0.0f);
  queue_->launch(*k.identity_parents, linear, parents_, count);
  auto fill_pixels = [&](compute::Buffer<float>& values, float value) {
    queue_->launch(*k.fill_per_particle, compute::NdRange::linear(count_ * kGroupSize, kGroupSize), values,
                   static_cast<unsigned>(window_.pixels()), value);
  };
  if (config_.occlusion_storage != OcclusionStorage::Off)
    fill_pixels(occlusion_, static_cast<float>(config_.occlusion.initial));
  if (config_.occlusion_storage == OcclusionStorage::PerPixelTime) {
    queue_->launch(*k.fill_time_indices, compute::NdRange::linear(count_ * kGroupSize, kGroupSize), occlusion_time_,
                   static_cast<unsigned>(window_.pixels()), static_cast<unsigned>(DT_TIME_NEVER));
    frame_times_->reset();
  }
  queue_->finish();
  frame_ = 0;
  time_ = 0;
  last_resampled_ = false;
  weighed_in_scratch_ = false;
}

void DeviceFilter::set_state(const std::vector<model::ParticleState>& particles, const std::vector<float>& occlusion,
                             const std::vector<float>& occlusion_time, const std::vector<double>& log_weights) {
  if (particles.size() != count_ || log_weights.size() != count_)
    throw InputError("set_state: expected " + std::to_string(count_) + " particles");
  const size_t rows = count_ * window_.pixels();
  if ((!occlusion.empty() && occlusion.size() != rows) || (!occlusion_time.empty() && occlusion_time.size() != rows))
    throw InputError("set_state: expected " + std::to_string(rows) + " occlusion values (particles x state window)");
  upload_particles(particles);
  log_weight_.upload(std::vector<float>(log_weights.begin(), log_weights.end()));
  if (!occlusion.empty()) occlusion_.upload(occlusion);
  if (!occlusion_time.empty()) occlusion_time_.upload(frame_times_->indices(occlusion_time));
  queue_->launch(*kernels_->identity_parents, compute::NdRange::linear(round_up(count_, kLinearGroup), kLinearGroup),
                 parents_, static_cast<unsigned>(count_));  // in queue order before the next frame's weigh
}

// Particle i's row is parents_[i] of the buffer (cl/weigh.cl folds the gather into the next frame).
template <typename T>
std::vector<T> DeviceFilter::rows_by_parent(const compute::Buffer<T>& rows) const {
  const std::vector<T> all = rows.download();
  const std::vector<unsigned> parents = parents_.download();
  const size_t row = window_.pixels();
  std::vector<T> gathered(count_ * row);
  for (size_t i = 0; i < count_; ++i)
    std::copy_n(all.begin() + static_cast<std::ptrdiff_t>(parents[i] * row), row,
                gathered.begin() + static_cast<std::ptrdiff_t>(i * row));
  return gathered;
}

std::vector<model::ParticleState> DeviceFilter::unpack(const compute::Buffer<float>& state) const {
  return unpack_particles(state.download());
}

std::vector<model::ParticleState> DeviceFilter::particles() const {
  return unpack(state_);
}

std::vector<float> DeviceFilter::occlusion_state() const {
  return config_.occlusion_storage == OcclusionStorage::Off ? std::vector<float>{} : rows_by_parent(occlusion_);
}

std::vector<float> DeviceFilter::occlusion_times() const {
  return config_.occlusion_storage == OcclusionStorage::PerPixelTime
             ? frame_times_->times(rows_by_parent(occlusion_time_))
             : std::vector<float>{};
}

// Resampling gathers into the scratch buffer and swaps, so the weighed states are left there.
std::vector<model::ParticleState> DeviceFilter::weighed_particles() const {
  return unpack(weighed_in_scratch_ ? scratch_state_ : state_);
}

// The atlas source's device work, timed from its event once the frame is done: nothing waits here.
compute::EventPtr DeviceFilter::render_atlas(StepTimings& timings) {
  return atlas_source_->draw(state_, atlas_, timings);
}

std::vector<float> DeviceFilter::last_atlas() const {
  if (render_weigh_ && !keep_atlas_)
    throw InputError("device filter: the atlas is drawn inside weigh and not kept (keep_atlas(true) keeps it)");
  if (atlas_source_->layout().tiles() < count_)
    throw InputError("device filter: the atlas holds " + std::to_string(atlas_source_->layout().tiles()) +
                     " tiles, drawn in turns: only the last turn's are left");
  std::vector<float> tiles = atlas_source_->layout().tiles_in_order(atlas_.download(), count_);
  if (const compute::Buffer<unsigned>* boxes = atlas_source_->tile_boxes()) {
    // Drawn only inside each pose's box: the rest of its tile is stale, and empty to weigh.
    const std::vector<unsigned> b = boxes->download();
    for (size_t i = 0; i < count_; ++i)
      for (size_t k = 0; k < pixels_; ++k) {
        const unsigned u = static_cast<unsigned>(k % static_cast<size_t>(camera_.width)),
                       v = static_cast<unsigned>(k / static_cast<size_t>(camera_.width));
        if (u - b[4 * i] >= b[4 * i + 2] || v - b[4 * i + 1] >= b[4 * i + 3]) tiles[i * pixels_ + k] = 0.0f;
      }
  }
  return tiles;
}

void DeviceFilter::keep_atlas(bool keep) {
  // render_weigh writes particle i's tile at i: the layout must hold them all.
  if (keep && render_weigh_ && atlas_source_->layout().tiles() < count_)
    throw InputError("device filter: an atlas of " + std::to_string(atlas_source_->layout().tiles()) +
                     " tiles cannot keep " + std::to_string(count_) + " particles' (TrackerConfig::atlas_particles)");
  keep_atlas_ = keep;
  if (render_weigh_) atlas_ = compute::Buffer<float>(*queue_, keep ? atlas_source_->layout().floats() : 1);
}

// One enqueue sequence per frame and one wait, the estimate's read in collect(): the depth goes up
// first (a blocking write waits for the work enqueued before it on this queue), the resampling decision
// is made on the device (summarize.cl's flag, read by the resampling kernels), and the device times are
// read from the events once the frame is done.
Estimate DeviceFilter::update(const DepthImage& depth, double dt) {
  enqueue_update(depth, dt);
  return collect();
}

void DeviceFilter::enqueue_update(const DepthImage& depth, double dt) {
  if (pending_) throw InputError("device filter: enqueue_update() while the previous frame is not collected");
  auto p = std::make_unique<Pending>();
  Kernels& k = *kernels_;
  // This frame's weigh writes its rows at next_window_ (an automatic window may have grown).
  reserve_state_rows(scratch_occlusion_, scratch_occlusion_time_, next_window_);
  time_ += dt;
  const Stopwatch upload;
  observed_.upload_enqueued(depth.data());  // the frame's launches follow it in order
  p->timings.upload_ms = upload.elapsed_ms();
  // The frame's launches as one batch (a CUDA graph, replayed frame after frame). Only where every
  // launch goes through the queue: the GL renderer's hand-off enqueues work of its own.
  compute::LaunchBatch batch(*queue_, atlas_source_->device_mesh() != nullptr);
  const unsigned count = static_cast<unsigned>(count_);
  const auto linear = compute::NdRange::linear(round_up(count_, kLinearGroup), kLinearGroup);
  const unsigned seed_lo = static_cast<unsigned>(config_.seed & 0xffffffffu),
                 seed_hi = static_cast<unsigned>(config_.seed >> 32);
  const dt_motion motion = dt > 0 ? model::motion_params(model::motion_step(config_.motion, dt), centre_) : dt_motion{};
  // For a small cloud render_weigh moves each particle itself (one launch fewer); propagate_ms is then
  // part of weigh_ms.
  if (dt > 0 && !propagates_in_weigh_)
    p->propagated = launch_step(*k.propagate, linear, state_, count, seed_lo, seed_hi, frame_, motion);

  unsigned now_index = 0;
  if (config_.occlusion_storage == OcclusionStorage::PerPixelTime) {
    now_index = frame_times_->begin_frame(static_cast<float>(time_));
    if (frame_times_->retire_due()) {
      // Before this frame's index is written anywhere; rare (cl/dt_time_index.h), so untimed.
      queue_->launch_untimed(*k.retire_time_indices, compute::NdRange::linear(256 * kGroupSize, kGroupSize),
                             occlusion_time_, static_cast<uint64_t>(count_ * window_.pixels()), now_index);
      frame_times_->retired();
    }
  }
  // Each particle's state from its parent's row (the last frame's resampling) into its own row of the
  // other buffer, which then becomes the state; the rows before stay for the refinement's prior. The
  // rows move with the state window (centred on the last estimate).
  const dt_window window = model::window_params(next_window_, window_, camera_, config_);
  window_ = next_window_;
  const auto per_particle_group = compute::NdRange::linear(count_ * kGroupSize, kGroupSize);
  if (render_weigh_)
    p->weighed.push_back(launch_step(
        *render_weigh_, per_particle_group, state_, render_weigh_mesh_->vertices, render_weigh_mesh_->triangles,
        render_weigh_mesh_->planes, render_weigh_mesh_->triangle_count(), render_weigh_mesh_->vertex_count(),
        model::camera_params(camera_, config_, render_weigh_mesh_->cull_back_faces), observed_, parents_, occlusion_,
        occlusion_time_, scratch_occlusion_, scratch_occlusion_time_, frame_times_->device(), log_likelihood_,
        log_weight_, model::model_params(config_), static_cast<float>(time_), now_index, static_cast<float>(dt), atlas_,
        static_cast<unsigned>(keep_atlas_), window, static_cast<unsigned>(dt > 0 && propagates_in_weigh_), seed_lo,
        seed_hi, frame_, motion));
  else
    // The atlas' tiles drawn and weighed in turns where it holds fewer than the particles.
    for (size_t first = 0, tiles = atlas_source_->layout().tiles(); first < count_; first += tiles) {
      const size_t n = std::min(tiles, count_ - first);
      p->rendered.push_back(tiles >= count_ ? render_atlas(p->timings)
                                            : atlas_source_->draw_range(state_, atlas_, first, n));
      p->weighed.push_back(launch_step(
          *k.weigh, compute::NdRange::linear(n * kGroupSize, kGroupSize), atlas_, observed_, parents_, occlusion_,
          occlusion_time_, scratch_occlusion_, scratch_occlusion_time_, frame_times_->device(), log_likelihood_,
          log_weight_, static_cast<unsigned>(pixels_), model::model_params(config_), static_cast<float>(time_),
          now_index, static_cast<float>(dt), atlas_source_->layout().kernel_args(), window,
          atlas_source_->tile_boxes() ? *atlas_source_->tile_boxes() : unused_boxes_,
          static_cast<unsigned>(atlas_source_->tile_boxes() != nullptr), static_cast<unsigned>(first)));
    }
  // The device starts on propagate and weigh (most of a small frame's first half) while the host
  // records the summary, and the summary while it records the refinement (on a slow host the device
  // had waited for the refinement's 19 launches to be recorded). The estimate's read hands over the
  // refinement, the batch's end the resampling.
  batch.flush();
  std::swap(occlusion_, scratch_occlusion_);
  std::swap(occlusion_time_, scratch_occlusion_time_);
  const float kl_threshold = model::float_threshold(config_.resample_kl_threshold);
  const float cx = static_cast<float>(centre_.x()), cy = static_cast<float>(centre_.y()),
              cz = static_cast<float>(centre_.z());
  // The refinement replaces the weighted mean's pose (it starts from the heaviest particle), so its
  // rotation mean is not iterated: 4 of the single group's 7 reductions, or 4 launches of the wide summary.
  const unsigned karcher_steps = refiner_ ? 0u : static_cast<unsigned>(DT_KARCHER_STEPS);
  if (wide_) {
    p->summarized = wide_->summarize(state_, log_weight_, log_likelihood_, weights_, estimate_, cx, cy, cz,
                                     kl_threshold, karcher_steps);
    batch.flush();
  } else if (!fit_summarizes_) {
    p->summarized = {launch_step(*k.summarize, compute::NdRange::linear(summary_group_, summary_group_), state_,
                                 log_weight_, log_likelihood_, weights_, estimate_, count, cx, cy, cz, kl_threshold,
                                 karcher_steps)};
    batch.flush();
  }
  // Before resample() overwrites parents_ with this frame's choice.
  if (refiner_) {
    const RefineInputs inputs{
        state_, observed_, scratch_occlusion_, scratch_occlusion_time_, frame_times_->device(), parents_, window,
        time_,  dt};
    const SummaryInputs summary{log_weight_, log_likelihood_, weights_, count, Eigen::Vector3f(cx, cy, cz),
                                kl_threshold};
    p->refined = refiner_->refine(estimate_, inputs, fit_summarizes_ ? &summary : nullptr);
  }
  // The estimate is complete: it goes to the host ahead of the resampling and the shift, which only the
  // next frame needs (they run while the host takes the estimate).
  estimate_.download_enqueued(std::span<float>(estimate_host_));
  p->resampling = resample();
  batch.submit();
  p->timings.enqueue_ms = p->clock.elapsed_ms();
  pending_ = std::move(p);
}

Estimate DeviceFilter::collect() {
  if (!pending_) throw InputError("device filter: collect() without an enqueued update");
  const std::unique_ptr<Pending> p = std::move(pending_);
  Estimate e;
  e.timings = p->timings;
  const Stopwatch wait;
  queue_->wait_enqueued_reads();  // the frame's one wait
  e.timings.wait_ms = wait.elapsed_ms();
  const float* est = estimate_host_.data();
  e.pose = Pose({est[DT_EST_TX], est[DT_EST_TX + 1], est[DT_EST_TX + 2]},
                Eigen::Quaterniond(est[DT_EST_QW], est[DT_EST_QW + 1], est[DT_EST_QW + 2], est[DT_EST_QW + 3]));
  e.linear_velocity = Eigen::Vector3d(est[DT_EST_VX], est[DT_EST_VX + 1], est[DT_EST_VX + 2]);
  e.angular_velocity = Eigen::Vector3d(est[DT_EST_WX], est[DT_EST_WX + 1], est[DT_EST_WX + 2]);
  e.effective_sample_size = est[DT_EST_ESS];
  e.max_log_likelihood = est[DT_EST_MAX_LL];
  e.mean_log_likelihood = est[DT_EST_MEAN_LL];
  e.resampled = est[DT_EST_RESAMPLE] != 0.0f;
  if (refiner_) {
    // The fit's H (float sums) made into the covariance here, in double, as the reference makes it.
    Eigen::Matrix<double, 6, 6> h;
    for (int r = 0, k = 0; r < 6; ++r)
      for (int c = 0; c <= r; ++c, ++k) h(r, c) = h(c, r) = est[DT_EST_NORMAL + k];
    e.covariance =
        model::fit_covariance(h, static_cast<int>(est[DT_EST_FIT_PIXELS]), refiner_->radius(), config_.refine);
    e.refine_iterations = static_cast<int>(est[DT_EST_REFINE_ITERATIONS]);
    // Counts, exact in float: the share as the reference divides them.
    e.confidence = est[DT_EST_MEASURED] > 0 ? static_cast<double>(est[DT_EST_VISIBLE]) / est[DT_EST_MEASURED] : 0.0;
  }
  last_resampled_ = e.resampled;
  weighed_in_scratch_ = true;
  next_window_ = model::next_state_window(window_, config_, extent_, e.pose, camera_, state_pixel_limit_);

  if (config_.step_timings) read_step_times(*p, e.timings);
  e.timings.total_ms = p->clock.elapsed_ms();
  ++frame_;
  return e;
}

// The steps' device times from their events, once the frame is done.
void DeviceFilter::read_step_times(Pending& p, StepTimings& timings) const {
  if (p.propagated) timings.propagate_ms = p.propagated->elapsed_ms();
  for (const auto& event : p.rendered)
    if (event) {
      timings.render_ms += event->elapsed_ms();
      timings.render_on_device = true;
    }
  for (const auto& event : p.weighed) timings.weigh_ms += event->elapsed_ms();
  timings.resample_ms += device_span_ms(p.summarized);
  for (const auto& event : p.resampling) timings.resample_ms += event->elapsed_ms();
  // The fit's launches as one span on the device (the spread layout enqueues dozens); the cloud's shift
  // is part of resample_particles, in resample_ms.
  if (!p.refined.empty()) timings.refine_ms = device_span_ms(p.refined);
}

// Enqueued every frame; the kernels read the device's decision (estimate_[DT_EST_RESAMPLE]). The
// state is gathered, or copied without resampling, into the scratch buffer, which becomes the state:
// the weighed states stay in scratch_state_. The per-pixel state is not copied: parents_ keeps the
// choice (the identity without resampling) and the next frame's weigh reads each row from its parent.
std::vector<compute::EventPtr> DeviceFilter::resample() {
  Kernels& k = *kernels_;
  const dt_philox4 words = dt_random_words(config_.seed, 0u, frame_, DT_STREAM_RESAMPLE, 0u);
  const auto linear = compute::NdRange::linear(round_up(count_, kLinearGroup), kLinearGroup);
  const unsigned count = static_cast<unsigned>(count_);
  const float u = dt_uniform01(words.v[0]);
  // With the refinement on, the children are moved by its correction as they are gathered.
  const Eigen::Vector3f centre = centre_.cast<float>();
  const compute::Buffer<float>& correction = refiner_ ? refiner_->correction() : no_correction_;
  const unsigned shift = refiner_ != nullptr;
  std::vector<compute::EventPtr> events;
  if (k.resample_scanning) {
    events.push_back(launch_step(*k.resample_scanning,
                                 compute::NdRange::linear(round_up(count_, kGroupSize), kGroupSize), weights_, parents_,
                                 count, u, estimate_, state_, scratch_state_, log_weight_, correction, centre.x(),
                                 centre.y(), centre.z(), shift));
  } else {
    if (wide_)
      events = wide_->prefix_sum(weights_, cumulative_, estimate_);
    else
      events.push_back(launch_step(*k.prefix_sum, compute::NdRange::linear(kGroupSize, kGroupSize), weights_,
                                   cumulative_, count, estimate_));
    events.push_back(launch_step(*k.resample_particles, linear, cumulative_, parents_, count, u, estimate_, state_,
                                 scratch_state_, log_weight_, correction, centre.x(), centre.y(), centre.z(), shift));
  }
  std::swap(state_, scratch_state_);
  return events;
}

std::vector<double> DeviceFilter::last_log_likelihoods() const {
  const std::vector<float> ll = log_likelihood_.download();
  return std::vector<double>(ll.begin(), ll.end());
}

std::vector<int> DeviceFilter::last_parents() const {
  std::vector<int> parents(count_);
  if (!last_resampled_) {
    std::iota(parents.begin(), parents.end(), 0);
    return parents;
  }
  const std::vector<unsigned> p = parents_.download();
  for (size_t i = 0; i < count_; ++i) parents[i] = static_cast<int>(p[i]);
  return parents;
}

}  // namespace depthtrack
