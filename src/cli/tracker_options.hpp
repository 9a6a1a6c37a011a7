#pragma once
// The tracker options that `track` and `demo` share, parsed into a TrackerConfig.
#include <CLI/CLI.hpp>
#include <depthtrack/tracker_config.hpp>
#include <string>

#include "cli/parse_values.hpp"  // the command line's value parsers, with the options

namespace depthtrack::cli {

struct TrackerOptions {
  // Where the flags land; resolve() copies only the flags given over the --config file's values.
  TrackerConfig flags;
  std::string config_file;  // --config: TrackerConfig as JSON (depthtrack/config_file.hpp)
  std::string resolution = "80x60";
  std::string occlusion = "per-pixel-time";
  std::string occlusion_window = "auto";
  std::string renderer = "kernel";  // parsed by resolve() (renderer_from_string)
  std::string refine = "on";
  std::string seed = std::to_string(TrackerConfig{}.seed);  // parsed by resolve() (parse_seed)
  CLI::Option *backend_option = nullptr, *renderer_option = nullptr, *gl_option = nullptr, *particles_option = nullptr,
              *resolution_option = nullptr, *occlusion_option = nullptr, *occlusion_window_option = nullptr,
              *refine_option = nullptr, *refine_iterations_option = nullptr, *seed_option = nullptr,
              *simplify_option = nullptr, *budget_option = nullptr, *min_particles_option = nullptr;

  void add_to(CLI::App& command);
  // The --config file's configuration (the defaults without one) with the flags given on the command
  // line over it, validated; throws InputError for malformed values. Where neither names the backend or the
  // GL path, $DEPTHTRACK_DEVICE and $DEPTHTRACK_GL do (cli/environment_defaults.hpp).
  TrackerConfig resolve() const;
};

}  // namespace depthtrack::cli
