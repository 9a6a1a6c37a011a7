#pragma once
// The tracker options that `track` and `demo` share, parsed into a TrackerConfig.
#include <CLI/CLI.hpp>
#include <depthtrack/tracker_config.hpp>
#include <string>

namespace depthtrack::cli {

struct TrackerOptions {
  TrackerConfig config;
  std::string resolution = "80x60";
  std::string occlusion = "per-pixel-time";
  std::string renderer = "kernel";         // parsed by resolve() (renderer_from_string)
  CLI::Option* renderer_option = nullptr;  // to tell an explicit --renderer from the default
  std::string refine = "on";

  void add_to(CLI::App& command);
  // Fills config from the parsed strings; throws InputError for malformed values.
  TrackerConfig resolve() const;
};

// "WxH" -> (W, H); InputError for anything else.
std::pair<int, int> parse_resolution(const std::string& text);
// "a b c ..." -> exactly n numbers; InputError naming the option otherwise.
std::vector<double> parse_numbers(const std::string& text, size_t n, const std::string& option);

}  // namespace depthtrack::cli
