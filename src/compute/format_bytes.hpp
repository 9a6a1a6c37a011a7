#pragma once
// "2.0 GiB": byte counts as people read them, for messages and `depthtrack info`.
#include <cstddef>
#include <cstdio>
#include <string>

namespace depthtrack::compute {

inline std::string format_bytes(size_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 4) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", value, units[unit]);
  return text;
}

}  // namespace depthtrack::compute
