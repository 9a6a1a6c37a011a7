#pragma once
/// @file
/// Every parameter of the tracking model, with the defaults of dbot; each comment gives its meaning and units.
#include <cmath>
#include <cstdint>
#include <string>

namespace depthtrack {

/// Per-pixel observation model.
struct ObservationModel {
  double sigma_constant = 0.003;  ///< sigma(y) = sigma_constant + sigma_quadratic * y^2 (metres)
  double sigma_quadratic = 0.0014247;
  double tail_weight = 0.01;             ///< w: weight of the uniform outlier tail
  double max_depth = 6.0;                ///< D: the tail is uniform on [0, D] (metres)
  double occluder_rate = std::log(2.0);  ///< lambda: exponential prior of occluder depth (1/m)
};

/// Two-state Markov chain of each pixel's occlusion, per second.
struct OcclusionModel {
  double p_occluded_stays = 0.7;       ///< a = P(occluded -> occluded)
  double p_visible_to_occluded = 0.1;  ///< b = P(visible -> occluded)
  double initial = 0.1;                ///< occlusion probability of a fresh particle's pixels
};

/// How the per-pixel occlusion state is kept (TrackerConfig::occlusion_storage).
enum class OcclusionStorage {
  PerPixelTime,  ///< (p, t_last) per pixel; only covered pixels are touched
  GlobalTime,    ///< p per pixel; every pixel is propagated each frame
  Off,           ///< p' = 0: no occlusion modelling
};
/// "per-pixel-time", "global-time" or "off".
const char* to_string(OcclusionStorage mode);
OcclusionStorage occlusion_storage_from_string(const std::string& name);  ///< throws InputError

/// Who draws the device filters' pose atlas (TrackerConfig::renderer).
enum class Renderer {
  Kernel,  ///< a compute kernel on the filter's device (cl/rasterize.cl)
  Gl,      ///< headless OpenGL, handed to the device (docs/architecture.md, "The pose atlas and GL")
  Cpu,     ///< the reference rasterizer on the host
};
const char* to_string(Renderer renderer);                ///< "kernel", "gl", "cpu"
Renderer renderer_from_string(const std::string& name);  ///< throws InputError naming the choices

/// How the device backends lay out the refinement (Refinement::layout); the reference has one way.
enum class RefineLayout {
  Auto,       ///< given 64-bit atomics: Spread for meshes of 2,048 triangles or more, on CUDA and on GPUs for
              ///< images over 160x120, else OneLaunch; without them OneGroup
  OneGroup,   ///< the whole fit in one work-group, one launch (cl/refine.cl)
  Spread,     ///< each step a draw and a sums launch over many work-groups, the last one solving (cl/refine_spread.cl)
  OneLaunch,  ///< Spread's draw and sums in one work-group, the whole fit one launch (needs 64-bit atomics)
};
const char* to_string(RefineLayout layout);                       ///< "auto", "one-group", "spread", "one-launch"
RefineLayout refine_layout_from_string(const std::string& name);  ///< throws InputError naming the choices

/// Damped random walk on the velocity (Ornstein-Uhlenbeck, discretized exactly over the real dt).
/// At dt = 1/reference_rate it is dbot's v' = damping v + sigma w, in the object's local frame
/// about the mesh's centre.
struct MotionModel {
  double damping = 0.8;          ///< velocity kept per reference frame
  double sigma_linear = 0.0025;  ///< metres per reference frame, per axis
  double sigma_angular = 0.02;   ///< radians per reference frame, per axis
  double reference_rate = 30.0;  ///< Hz at which the three numbers above are given
};

/// After weighting, a few Gauss-Newton / Levenberg-Marquardt steps move the heaviest particle's pose to the maximum
/// of the same per-pixel likelihood (IRLS: each pixel weighted by the responsibility of its visible
/// component, with the heaviest particle's occlusion probabilities before this frame's update), and the whole particle
/// cloud is shifted by the correction so the filter stays consistent with the reported pose.
struct Refinement {
  bool enabled = true;
  int iterations = 8;     ///< at most this many Gauss-Newton steps per frame (each renders the pose once more)
  double damping = 1e-2;  ///< Levenberg-Marquardt lambda on diag(H); after a rejected step tenfold, at least 1
  /// Converged: the next step would move no point of the mesh farther than this (metres; |dt| + radius |dw|),
  /// so it is not tried. 0 always takes every step.
  double converged_motion = 5e-5;
  double min_incidence = 0.15;  ///< pixels whose |cos| between surface normal and ray is below this are dropped
  /// The fit's depth noise as a share of the observation model's sigma(y), which the particles' weights
  /// use (the filter's sigma is wide, so that the cloud does not collapse onto a wrong pose). Below 1 the
  /// fit gives pixels a few millimetres off (edges, the model's own error) less say; 1 is the default
  /// (docs/user/configuration.md, `refine.noise_scale`, says why). The covariance and the confidence's band
  /// stay at the filter's sigma.
  double noise_scale = 1.0;
  /// A second stage: after the steps at noise_scale, up to `iterations` more at this share of sigma(y)
  /// (0: none). The first stage's wide likelihood draws the pose in from afar, the second's narrow one
  /// then gives pixels a few millimetres off (edges, occluders' rims, the model's own error) less say,
  /// without the narrow one's smaller reach. The covariance comes from the last stage's H. Every backend
  /// fits both stages (docs/user/configuration.md, `refine.fine_noise_scale`: what it gains and costs).
  double fine_noise_scale = 0.35;
  RefineLayout layout = RefineLayout::Auto;  ///< device backends only: the same fit, laid out differently
};

/// When an estimate counts as lost, from its confidence (Estimate::confidence, a calibrated probability).
struct LossModel {
  double pixel_sigmas = 3.0;   ///< |y - y_hat| within this many sigma(y): the object is seen there
  double lost_below = 0.5;     ///< a frame below this confidence is reported lost
  int search_after = 3;        ///< this many lost frames in a row start a search each frame (recovery)
  double found_above = 0.75;   ///< a search candidate this confident ends lost
  double found_outline = 0.5;  ///< and this share of its outline sees past its edge
};

/// Where each particle keeps its per-pixel occlusion state (docs/architecture.md, "The occlusion
/// state window"): a window of the working image, centred each frame on the previous estimate's projected mesh
/// centre and clamped inside the image. Its pixels keep the model's state from frame to frame; every other
/// pixel is taken as fresh (occlusion.initial at time 0, aged to now) and still adds its likelihood term,
/// so only the memory of occlusion outside the window is given up, for memory and traffic proportional to
/// the window instead of the image.
///   automatic (the default, width and height 0): sized at each start to hold the projection of the
///     mesh's bounding box at that pose with a margin, and grown whenever the estimate's would no longer
///     fit (model::automatic_window_size); a window that holds every pixel the particles cover keeps the
///     whole image's numbers exactly.
///   width x height: a fixed window (0 in one of them: that whole dimension).
///   automatic false, 0 x 0: the whole image, the model as MODEL.md writes it.
struct OcclusionWindow {
  int width = 0;          ///< pixels of the working image; 0: automatic, or the whole width
  int height = 0;         ///< pixels of the working image; 0: automatic, or the whole height
  bool automatic = true;  ///< only with width and height 0

  /// The whole image: the model as MODEL.md writes it.
  static OcclusionWindow whole_image() { return {0, 0, false}; }
  /// A fixed window of width x height working pixels (0 in one: that whole dimension).
  static OcclusionWindow fixed(int width, int height) { return {width, height, false}; }
  /// Whether the window is sized and grown by the tracker.
  bool is_automatic() const { return automatic && width == 0 && height == 0; }
};
/// "auto", "full" or "WxH" (positive integers); throws InputError naming the choices.
OcclusionWindow occlusion_window_from_string(const std::string& text);

/// Global search while lost.
struct RecoveryModel {
  bool enabled = true;     ///< search while lost (off: a lost track stays lost until initialize())
  double budget_ms = 500;  ///< wall-clock per lost frame for the search
};

/// Every parameter of a Tracker; the defaults are dbot's model. validate() checks them all.
struct TrackerConfig {
  ObservationModel observation;                                         ///< each pixel's likelihood
  OcclusionModel occlusion;                                             ///< each pixel's occlusion chain
  MotionModel motion;                                                   ///< the particles' motion noise
  Refinement refine;                                                    ///< the fit after weighting
  OcclusionStorage occlusion_storage = OcclusionStorage::PerPixelTime;  ///< how the occlusion state is kept
  OcclusionWindow occlusion_window;                                     ///< where it is kept
  /// Metres: the tracker draws the mesh simplified by quadric edge collapse (meshoptimizer) while its
  /// estimate of the surface's displacement stays within this (the farthest original vertex then lies
  /// up to about twice as far); 0 draws it as given. The default is a sixth of the least depth noise the
  /// observation model assumes (sigma_constant, 3 mm): it draws scanned meshes of many thousand triangles
  /// with a few hundred to a few thousand (Tracker::drawn_triangles); README, "Simplified mesh", gives what
  /// that saves in time and costs in accuracy.
  /// A small part is simplified within 2 % of its radius at most, so that it keeps its shape. Set 0 for
  /// exact synthetic depth of a fine mesh, where the fit resolves tenths of a millimetre.
  double simplify_error = 0.0005;
  int particles = 200;  ///< the particle cloud's size (with budget_ms: the most a frame runs)
  /// Milliseconds a frame may take; 0 (the default): off, every frame runs `particles`. On (any backend; a device
  /// backend times its steps on the device), each frame's count is chosen from the tracker's own measured times to
  /// finish within it, in [min_particles, particles]: fewer while confident and the fit determines every direction,
  /// up to what the budget affords when confidence falls, the fit leaves a direction weak, after a gap or while
  /// lost; the frame after initialize() runs what recovery.budget_ms affords: it searches the start's spread.
  double budget_ms = 0;
  int min_particles = 10;  ///< the fewest particles a budgeted frame runs
  /// Device backends with the kernel renderer, where a tile does not fit in work-group memory (above
  /// 80x60): the pose atlas holds at most this many particles' tiles (particles x pixels floats in all:
  /// 37 GB for 30,000 particles at 640x480), drawn and weighed in turns, the same numbers as all at once.
  /// 0: as many as one buffer of the device holds (its largest allocation: a quarter of the memory on
  /// NVIDIA's OpenCL). The GL and cpu renderers keep every tile.
  int atlas_particles = 0;
  int width = 80;                      ///< working resolution: the sensor image is decimated to it
  int height = 60;                     ///< working resolution: the sensor image is decimated to it
  double resample_kl_threshold = 2.0;  ///< resample when log N - H(w) exceeds this
  double near_plane = 0.05;            ///< metres: rendering clips geometry closer than this
  /// Seconds: the longest gap between frames the motion model bridges. A longer one is propagated as
  /// this long, so that the particles' spread stays bounded (the motion noise grows with the gap without
  /// bound, and a cloud spread blindly over the scene settles on whatever surface fits), and then the
  /// object is searched for around its last pose before the track is trusted again (Tracker::update).
  double max_time_step = 0.2;
  uint64_t seed = 1;  ///< the filter's random numbers: the same seed and frames, the same estimates
  /// reference, opencl, opencl:pocl, opencl:nvidia, opencl:<platform>.<device>, cuda, cuda:<n>;
  /// empty: reference (see resolved_backend()). The library reads no environment; the depthtrack
  /// command fills this from $DEPTHTRACK_DEVICE when --backend is not given.
  std::string backend;
  /// Who draws the device filters' pose atlas: Kernel (a compute kernel on the filter's device,
  /// the default; docs/performance.md compares them), Gl (OpenGL, headless: EGL device,
  /// EGL surfaceless or OSMesa, gl_path picks one; the atlas reaches the kernels by CUDA-GL
  /// interop, a GL-OpenCL bridge or a staged copy) or Cpu (the reference rasterizer on the host).
  Renderer renderer = Renderer::Kernel;
  /// The headless GL path of the Gl renderer: auto (each in turn: EGL device, EGL surfaceless, OSMesa) or
  /// only egl-device, egl-surfaceless or osmesa. The depthtrack command fills it from --gl or $DEPTHTRACK_GL.
  std::string gl_path = "auto";
  LossModel loss;          ///< when a track counts as lost
  RecoveryModel recovery;  ///< the search while lost
  /// Compute backends: time each step of a frame on the device (StepTimings' propagate, render, weigh,
  /// resample and refine), for profiling (depthtrack bench and depthtrack_bench turn it on). Off, those
  /// read 0 and the frame goes without their timing records (two per step on the device, and their
  /// reading after it, a small share of a frame; from 16,384 particles the many-group summary keeps its
  /// own two); total_ms and the host's times stay. The host backends time
  /// their steps either way.
  bool step_timings = false;

  /// Throws InputError naming the first impossible value.
  void validate() const;
  /// The backend this configuration selects: `backend`, or reference when it is empty.
  std::string resolved_backend() const;
};

}  // namespace depthtrack
