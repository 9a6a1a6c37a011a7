#include "cli/init_spread.hpp"

#include <cstdio>
#include <numbers>

#include "cli/parse_values.hpp"

namespace depthtrack::cli {

std::string default_init_spread() {
  char text[64];
  std::snprintf(text, sizeof text, "%g %g", InitialSpread::kDefaultMetres, InitialSpread::kDefaultDegrees);
  return text;
}

InitialSpread parse_init_spread(const std::string& text) {
  const auto v = parse_numbers(text, 2, "--init-spread");
  return {v[0], v[1] * std::numbers::pi / 180.0};
}

}  // namespace depthtrack::cli
