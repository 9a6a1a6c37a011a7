#pragma once
// The one list of TrackerConfig's fields: name, member, unit and a line of help for each, nested structs
// included. The JSON configuration file (io/config_json.cpp), its equality and the Python
// attributes (python/src/bind_config.cpp) are all generated from it; a field added to
// tracker_config.hpp must be added here (tests/io/test_config_file.cpp checks none is missing).
#include <depthtrack/tracker_config.hpp>
#include <string>
#include <tuple>
#include <type_traits>

namespace depthtrack::config_fields {

// Enumerations the file and the bindings spell as strings: to_string() and this parse.
template <typename T>
concept NamedEnum =
    std::is_same_v<T, OcclusionStorage> || std::is_same_v<T, Renderer> || std::is_same_v<T, RefineLayout>;
inline void parse_named(const std::string& text, OcclusionStorage& value) {
  value = occlusion_storage_from_string(text);
}
inline void parse_named(const std::string& text, Renderer& value) {
  value = renderer_from_string(text);
}
inline void parse_named(const std::string& text, RefineLayout& value) {
  value = refine_layout_from_string(text);
}
// The choices, for messages.
inline const char* named_choices(const OcclusionStorage*) {
  return "per-pixel-time, global-time or off";
}
inline const char* named_choices(const Renderer*) {
  return "kernel, gl or cpu";
}
inline const char* named_choices(const RefineLayout*) {
  return "auto, one-group, spread or one-launch";
}

template <typename Struct, typename Member>
struct Field {
  const char* name;
  Member Struct::*member;
  const char* unit;  // of the value: "m", "ms", "pixels", "probability", ...; "" for none (a count, a struct)
  const char* help;
  using struct_type = Struct;
  using member_type = Member;
};

template <typename Struct, typename Member>
constexpr Field<Struct, Member> field(const char* name, Member Struct::*member, const char* unit, const char* help) {
  return {name, member, unit, help};
}

inline auto fields_of(const ObservationModel*) {
  using S = ObservationModel;
  return std::tuple{
      field("sigma_constant", &S::sigma_constant, "m",
            "depth noise sigma(y) = sigma_constant + sigma_quadratic y^2 (m)"),
      field("sigma_quadratic", &S::sigma_quadratic, "1/m", "quadratic term of the depth noise (1/m)"),
      field("tail_weight", &S::tail_weight, "share", "weight of the uniform outlier tail, in [0, 1)"),
      field("max_depth", &S::max_depth, "m", "the tail is uniform on [0, max_depth]; deeper readings are missing (m)"),
      field("occluder_rate", &S::occluder_rate, "1/m", "exponential prior of an occluder's depth (1/m)"),
  };
}

inline auto fields_of(const OcclusionModel*) {
  using S = OcclusionModel;
  return std::tuple{
      field("p_occluded_stays", &S::p_occluded_stays, "probability", "P(occluded -> occluded) per second"),
      field("p_visible_to_occluded", &S::p_visible_to_occluded, "probability", "P(visible -> occluded) per second"),
      field("initial", &S::initial, "probability", "occlusion probability of a fresh particle's pixels"),
  };
}

inline auto fields_of(const MotionModel*) {
  using S = MotionModel;
  return std::tuple{
      field("damping", &S::damping, "share", "velocity kept per reference frame, in (0, 1)"),
      field("sigma_linear", &S::sigma_linear, "m", "linear velocity noise per reference frame, per axis (m)"),
      field("sigma_angular", &S::sigma_angular, "rad", "angular velocity noise per reference frame, per axis (rad)"),
      field("reference_rate", &S::reference_rate, "Hz", "rate at which the three above are given (Hz)"),
  };
}

inline auto fields_of(const Refinement*) {
  using S = Refinement;
  return std::tuple{
      field("enabled", &S::enabled, "", "fit the heaviest particle to the likelihood's maximum and shift the cloud"),
      field("iterations", &S::iterations, "steps", "Gauss-Newton steps per frame, in [0, 100]"),
      field("damping", &S::damping, "", "Levenberg-Marquardt lambda on diag(H)"),
      field("converged_motion", &S::converged_motion, "m",
            "stop when the next step moves no mesh point farther than this (m); 0 takes every step"),
      field("min_incidence", &S::min_incidence, "cosine", "pixels whose |cos(normal, ray)| is below this are left out"),
      field("noise_scale", &S::noise_scale, "share",
            "the fit's depth noise as a share of the observation's sigma(y), in (0, 10]; 1 fits at the filter's"),
      field("fine_noise_scale", &S::fine_noise_scale, "share",
            "a second stage of steps at this share of sigma(y), in [0, 10]; 0: none"),
      field("layout", &S::layout, "",
            "device backends: auto, one-group (the fit in one work-group), spread (its steps over many) or "
            "one-launch (spread's steps in one work-group)"),
  };
}

inline auto fields_of(const LossModel*) {
  using S = LossModel;
  return std::tuple{
      field("pixel_sigmas", &S::pixel_sigmas, "sigma(y)",
            "|y - y_hat| within this many sigma(y): the object is seen there"),
      field("lost_below", &S::lost_below, "probability",
            "a frame below this confidence (a probability) is reported lost"),
      field("search_after", &S::search_after, "frames", "this many lost frames in a row start a search each frame"),
      field("found_above", &S::found_above, "probability", "a search candidate this confident ends lost"),
      field("found_outline", &S::found_outline, "share",
            "and this share of its outline (where not against a nearer surface) sees past its edge"),
  };
}

inline auto fields_of(const RecoveryModel*) {
  using S = RecoveryModel;
  return std::tuple{
      field("enabled", &S::enabled, "", "search the frame again while lost"),
      field("budget_ms", &S::budget_ms, "ms", "wall-clock budget of that search per lost frame (ms)"),
  };
}

inline auto fields_of(const OcclusionWindow*) {
  using S = OcclusionWindow;
  return std::tuple{
      field("width", &S::width, "pixels", "pixels of the working image; 0: the whole width (or automatic)"),
      field("height", &S::height, "pixels", "pixels of the working image; 0: the whole height (or automatic)"),
      field("automatic", &S::automatic, "",
            "with width and height 0: sized to the object's projection at the start and grown with it "
            "(false: the whole image)"),
  };
}

inline auto fields_of(const TrackerConfig*) {
  using S = TrackerConfig;
  return std::tuple{
      field("observation", &S::observation, "", "per-pixel observation model"),
      field("occlusion", &S::occlusion, "", "occlusion Markov chain of each pixel"),
      field("motion", &S::motion, "", "damped random walk on the velocity"),
      field("refine", &S::refine, "", "pose refinement after weighting"),
      field("occlusion_storage", &S::occlusion_storage, "", "per-pixel-time, global-time or off"),
      field("occlusion_window", &S::occlusion_window, "",
            "where particles keep occlusion state: a window around the estimate, automatic by default"),
      field("simplify_error", &S::simplify_error, "m",
            "the mesh is drawn simplified to within this distance of its surface (m; at most 2 % of its radius); "
            "0: as given"),
      field("particles", &S::particles, "particles", "number of particles (with budget_ms: the most a frame runs)"),
      field("budget_ms", &S::budget_ms, "ms",
            "any backend: the particle count follows each frame's need within this many ms a frame; 0: off"),
      field("min_particles", &S::min_particles, "particles", "with budget_ms: the fewest particles a frame runs"),
      field("atlas_particles", &S::atlas_particles, "particles",
            "kernel renderer above 80x60: the pose atlas holds at most this many tiles, drawn and weighed in "
            "turns; 0: as many as one device buffer holds"),
      field("width", &S::width, "pixels", "working resolution: the sensor image is decimated to it"),
      field("height", &S::height, "pixels", "working resolution height"),
      field("resample_kl_threshold", &S::resample_kl_threshold, "nats", "resample when log N - H(w) exceeds this"),
      field("near_plane", &S::near_plane, "m", "rendering clips geometry closer than this (m)"),
      field("max_time_step", &S::max_time_step, "s",
            "the longest gap between frames the motion model bridges; a longer one is propagated as this long and "
            "searched around the last pose (s)"),
      field("seed", &S::seed, "", "random seed: the same seed gives the same particles on every backend"),
      field("backend", &S::backend, "",
            "reference, opencl, opencl:pocl, opencl:nvidia, opencl:<p>.<d>, cuda, cuda:<n>; empty: reference"),
      field("renderer", &S::renderer, "", "who draws the device filters' pose atlas: kernel, gl or cpu"),
      field("gl_path", &S::gl_path, "", "the gl renderer's headless GL: auto, egl-device, egl-surfaceless or osmesa"),
      field("loss", &S::loss, "", "when an estimate counts as lost"),
      field("recovery", &S::recovery, "", "global search while lost"),
      field("step_timings", &S::step_timings, "",
            "time each step of a frame on the device (profiling); off: those times read 0, total_ms stays"),
  };
}

// A struct with a field list (recursed into) rather than a value.
template <typename T>
concept Struct = requires {
  fields_of(static_cast<const T*>(nullptr));
};

// Calls visit(field) for each field of S, in declaration order.
template <Struct S, typename Visit>
void for_each_field(Visit&& visit) {
  std::apply([&](const auto&... f) { (visit(f), ...); }, fields_of(static_cast<const S*>(nullptr)));
}

// Field-by-field equality, nested structs included.
template <Struct S>
bool equal(const S& a, const S& b) {
  bool same = true;
  for_each_field<S>([&](const auto& f) {
    using M = typename std::decay_t<decltype(f)>::member_type;
    if constexpr (Struct<M>)
      same = same && equal(a.*f.member, b.*f.member);
    else
      same = same && a.*f.member == b.*f.member;
  });
  return same;
}

}  // namespace depthtrack::config_fields
