#include "host_memory.hpp"

#include <cmath>
#include <fstream>
#include <string>

namespace depthtrack::bench {

bool reset_peak_resident() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return static_cast<bool>(clear);
}

namespace {
// A "Name:  1234 kB" line of /proc/self/status, in MiB.
double status_mib(const std::string& name) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(name, 0) == 0) return std::stod(line.substr(name.size())) / 1024.0;
  return NAN;
}
}  // namespace

double peak_resident_mib() {
  return status_mib("VmHWM:");
}

double resident_mib() {
  return status_mib("VmRSS:");
}

}  // namespace depthtrack::bench
