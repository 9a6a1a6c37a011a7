#include "cli/tracker_options.hpp"

#include <cstdio>
#include <depthtrack/config_file.hpp>
#include <depthtrack/error.hpp>

#include "cli/environment_defaults.hpp"
#include "compute/backend.hpp"

namespace depthtrack::cli {

void TrackerOptions::add_to(CLI::App& command) {
  command
      .add_option("--config", config_file,
                  "JSON file of tracker parameters, any subset (`depthtrack config --dump` prints every one with "
                  "its default); the flags below override it")
      ->check(CLI::ExistingFile);
  // The device selectors come from the backend registry, so a new backend appears here by itself.
  std::string selectors;
  for (const auto& backend : compute::backends()) selectors += ", " + backend.grammar;
  backend_option = command.add_option("--backend", flags.backend,
                                      "Filter implementation: reference (sequential CPU), cpu (the reference on "
                                      "every core; cpu:N: N threads; the same results)" +
                                          selectors +
                                          " (`depthtrack info` lists devices); default: "
                                          "$DEPTHTRACK_DEVICE, else reference");
  renderer_option =
      command.add_option("--renderer", renderer,
                         "Who draws the pose atlas for device backends: kernel (a compute kernel on the device itself, "
                         "the fastest), gl (headless OpenGL, the path --gl picks) or cpu (the reference rasterizer on "
                         "the host)");
  renderer_option->capture_default_str();
  gl_option = command.add_option("--gl", flags.gl_path,
                                 "The gl renderer's headless OpenGL: auto (EGL device, EGL surfaceless, then OSMesa), "
                                 "egl-device, egl-surfaceless or osmesa; default: $DEPTHTRACK_GL, else auto");
  particles_option =
      command
          .add_option("--particles", flags.particles, "Number of particles (with --budget-ms: the most a frame runs)")
          ->capture_default_str();
  budget_option = command
                      .add_option("--budget-ms", flags.budget_ms,
                                  "Milliseconds a frame may take (any backend): each frame's particle "
                                  "count is chosen from the tracker's measured times, fewer while the estimate is "
                                  "confident, more when it is not; 0: off, every frame runs --particles")
                      ->capture_default_str();
  min_particles_option =
      command.add_option("--min-particles", flags.min_particles, "With --budget-ms: the fewest particles a frame runs")
          ->capture_default_str();
  resolution_option =
      command
          .add_option("--resolution", resolution,
                      "Working resolution WxH; the sensor image is decimated to it by an integer factor")
          ->capture_default_str();
  occlusion_option = command
                         .add_option("--occlusion", occlusion,
                                     "Occlusion model storage: per-pixel-time (p and last update time per pixel), "
                                     "global-time (p only, every pixel propagated each frame) or off")
                         ->capture_default_str();
  occlusion_window_option =
      command
          .add_option("--occlusion-window", occlusion_window,
                      "Where each particle keeps its occlusion state, a window around the last estimate (pixels "
                      "outside it are taken as fresh): auto (sized to the object's projection with a margin at the "
                      "start, grown as it grows), WxH pixels of the working image, or full (the whole image, the "
                      "model as written; the most memory and traffic)")
          ->capture_default_str();
  simplify_option = command
                        .add_option("--simplify-error", flags.simplify_error,
                                    "Draw the mesh simplified so that its surface moves at most this many metres (e.g. "
                                    "0.0005: a 16k-triangle scan keeps 250-3,200 triangles at 80x60); 0: as given")
                        ->capture_default_str();
  refine_option =
      command
          .add_option("--refine", refine,
                      "on: after weighting, fit the estimate to the likelihood's maximum (damped Gauss-Newton on the "
                      "per-pixel depth residuals) and shift the particle cloud with it; off: the particle filter alone")
          ->capture_default_str();
  refine_iterations_option =
      command
          .add_option("--refine-iterations", flags.refine.iterations, "Gauss-Newton steps per frame of the refinement")
          ->capture_default_str();
  seed_option =
      command.add_option("--seed", seed, "Random seed: the same seed gives the same particles on every backend")
          ->capture_default_str();
}

TrackerConfig TrackerOptions::resolve() const {
  TrackerConfig c = config_file.empty() ? TrackerConfig{} : load_tracker_config(config_file);
  const auto given = [](const CLI::Option* option) { return option && option->count() > 0; };
  if (given(backend_option)) c.backend = flags.backend;
  if (!given(backend_option) && c.backend.empty()) c.backend = device_from_environment();
  if (given(gl_option)) c.gl_path = flags.gl_path;
  if (!given(gl_option) && c.gl_path == "auto") c.gl_path = gl_path_from_environment();
  if (given(renderer_option)) c.renderer = renderer_from_string(renderer);
  if (given(particles_option)) c.particles = flags.particles;
  if (given(budget_option)) c.budget_ms = flags.budget_ms;
  if (given(min_particles_option)) c.min_particles = flags.min_particles;
  if (given(resolution_option)) std::tie(c.width, c.height) = parse_resolution(resolution);
  if (given(occlusion_option)) c.occlusion_storage = occlusion_storage_from_string(occlusion);
  if (given(occlusion_window_option)) {
    try {
      c.occlusion_window = occlusion_window_from_string(occlusion_window);
    } catch (const InputError&) {
      throw InputError("--occlusion-window '" + occlusion_window + "' is not auto, full or WxH with positive integers");
    }
  }
  if (given(refine_option)) {
    if (refine != "on" && refine != "off") throw InputError("--refine '" + refine + "' is not on or off");
    c.refine.enabled = refine == "on";
  }
  if (given(refine_iterations_option)) c.refine.iterations = flags.refine.iterations;
  if (given(seed_option)) c.seed = parse_seed(seed, "--seed");
  if (given(simplify_option)) c.simplify_error = flags.simplify_error;
  c.validate();
  // The reference filter (cpu: on threads) always draws with its own rasterizer: say so rather than ignore it.
  const std::string backend = c.resolved_backend();
  if (given(renderer_option) && (backend == "reference" || backend.rfind("cpu", 0) == 0))
    std::fprintf(stderr,
                 "depthtrack: warning: --renderer %s has no effect with the %s backend (it draws with its own "
                 "rasterizer); it applies to the opencl and cuda backends\n",
                 renderer.c_str(), backend == "reference" ? "reference" : "cpu");
  return c;
}

}  // namespace depthtrack::cli
