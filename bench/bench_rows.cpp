#include "bench_rows.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace depthtrack::bench {

void print_header() {
  std::printf("backend,platform,device,driver,test,metric,unit,value\n");
}

void print_row(const Row& r) {
  std::printf("%s,%s,\"%s\",%s,%s,%s,%s,%.6g\n", r.backend.c_str(), r.platform.c_str(), r.device.c_str(),
              r.driver.c_str(), r.test.c_str(), r.metric.c_str(), r.unit.c_str(), r.value);
  std::fflush(stdout);
}

double median(std::vector<double> samples) {
  if (samples.empty()) return 0;
  const auto middle = samples.begin() + static_cast<std::ptrdiff_t>(samples.size() / 2);
  std::nth_element(samples.begin(), middle, samples.end());
  return *middle;
}

std::string cpu_name() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

}  // namespace depthtrack::bench
