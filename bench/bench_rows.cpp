#include "bench_rows.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace depthtrack::bench {

void print_header() {
  std::printf("backend,platform,device,driver,test,metric,unit,value\n");
}

void print_row(const Row& r) {
  std::printf("%s,%s,\"%s\",%s,%s,%s,%s,%.6g\n", r.backend.c_str(), r.platform.c_str(), r.device.c_str(),
              r.driver.c_str(), r.test.c_str(), r.metric.c_str(), r.unit.c_str(), r.value);
  std::fflush(stdout);
}

void print_status(const std::string& backend, const std::string& test, const std::string& reason) {
  std::string line = reason.substr(0, reason.find('\n'));
  for (char& ch : line)
    if (ch == '"') ch = '\'';
  std::printf("%s,%s,\"-\",-,%s,status,\"%s\",nan\n", backend.c_str(), backend.c_str(), test.c_str(), line.c_str());
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

std::filesystem::path data_dir() {
  const char* env = std::getenv("DEPTHTRACK_DATA_DIR");
  return env ? env : DEPTHTRACK_DATA_DIR;
}

Mesh bench_mesh(std::string& name) {
  const auto handset = data_dir() / "meshes/dbot/handset.obj";
  if (std::filesystem::exists(handset)) {
    name = "handset";
    return Mesh::load(handset);
  }
  std::fprintf(stderr, "note: %s is absent; benchmarking the built-in mesh instead\n", handset.c_str());
  name = "builtin";
  return builtin_demo_mesh();
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  return parts;
}

std::string compact_number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace depthtrack::bench
