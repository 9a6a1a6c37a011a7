#pragma once
// What `depthtrack bench` measures, as rows of results.json, and `bench compare`'s table of several
// such files. One row per (backend, test, metric): the median and 95th percentile of its samples.
#include <filesystem>
#include <string>
#include <vector>

namespace depthtrack::cli {

struct BenchRow {
  std::string backend, platform, device, driver, commit, test, metric, unit;
  double median = 0, p95 = 0;  // NaN is written as null
  int samples = 0;
};

struct BenchResults {
  std::vector<BenchRow> rows;
  std::vector<std::string> notes;  // cases skipped or failed, and why
};

// Median (mean of the middle two for an even count) and nearest-rank 95th percentile; NaN when empty.
double median_of(std::vector<double> samples);
double p95_of(std::vector<double> samples);

// Writes results as JSON to path through path.partial and a rename, so a failed run leaves an
// earlier file as it was. Error naming the file when it cannot be written.
void write_results(const BenchResults& results, const std::filesystem::path& path);
// Reads a results.json; InputError naming the file and the problem (not JSON, no rows, a row
// without one of the columns, a column of the wrong type).
BenchResults read_results(const std::filesystem::path& path);

// The cross-vendor table: one column per (file, backend) in the order given, one line per test and
// metric, each value with its ratio to the first column's.
std::string compare_table(const std::vector<std::pair<std::string, BenchResults>>& files);

}  // namespace depthtrack::cli
