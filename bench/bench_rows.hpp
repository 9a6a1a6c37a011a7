#pragma once
// Benchmark output in clpeak's shape: one CSV row per measurement, so runs on different machines
// and backends can be concatenated and compared.
#include <depthtrack/mesh.hpp>
#include <filesystem>
#include <string>
#include <vector>

namespace depthtrack::bench {

struct Row {
  std::string backend, platform, device, driver, test, metric, unit;
  double value;
};

void print_header();
void print_row(const Row& row);
// A case that could not run: metric "status", the reason (quoted, first line) as its unit, no value.
void print_status(const std::string& backend, const std::string& test, const std::string& reason);
// Median of the samples (they are reordered).
double median(std::vector<double> samples);
// The host CPU's model name, from /proc/cpuinfo.
std::string cpu_name();
// A number as a test name carries it: 0.5 -> "0.5", 2 -> "2" (six significant digits at most).
std::string compact_number(double value);
// The third-party data folder: DEPTHTRACK_DATA_DIR from the environment, else the configured one.
std::filesystem::path data_dir();
// The thesis' handset from the data folder (DEPTHTRACK_DATA_DIR), else the built-in mesh; its name.
Mesh bench_mesh(std::string& name);
// "a,b,c" -> {"a", "b", "c"}.
std::vector<std::string> split(const std::string& text);

}  // namespace depthtrack::bench
