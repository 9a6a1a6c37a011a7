#pragma once
// The thesis' evaluation (chapter 6) as cases for `depthtrack bench`: frame time against the particle
// count, the resolution and the triangle count, the occlusion storage modes, each frame split into its
// steps with the bytes they move, and the speedup over the sequential reference.
#include <depthtrack/mesh.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker_config.hpp>
#include <string>
#include <vector>

#include "cli/bench_results.hpp"
#include "compute/device_info.hpp"

namespace depthtrack::cli {

// Which cases a run has: --quick (CI's CPU in minutes), the full grid (a GPU), or the test grid.
struct BenchGrid {
  std::vector<int> particle_counts;  // the particles sweep, at 80x60
  std::vector<std::pair<int, int>> resolutions;
  int particles_at_resolution = 0, particles_at_triangles = 0, particles_at_occlusion = 0;
  int particles_at_latency = 0;  // the latency case: 80x60, steps untimed, as a tracker runs
  int frames = 0;                // per case, the first two not timed
  double cpu_max_work = 0;       // particles x pixels above which the reference and CPU devices skip a case
};
BenchGrid quick_grid();
BenchGrid full_grid();
BenchGrid test_grid();

// A mesh with the synthetic occluded sequence every case of it tracks (made once).
struct BenchMesh {
  std::string name;
  Mesh mesh;
  std::vector<SynthFrame> frames;
};
BenchMesh make_bench_mesh(const std::string& name, Mesh mesh, int frames);

// What to run on: "reference", the reference on a thread pool ("cpu", "cpu:N") or a device selector,
// with the facts results.json names it by.
struct BenchTarget {
  std::string backend, platform, device, driver;
  bool cpu = true;             // the reference or a CPU device: cases beyond cpu_max_work are skipped
  bool on_device = false;      // a compute device's filter: device_memory is reported
  compute::DeviceInfo info{};  // what the device reports: the filter's FramePlan, which the rows' sizes follow
};
// Opens each device once (InputError from the compute layer for an unknown or absent one; cpu:N
// with an impossible N).
BenchTarget describe_target(const std::string& backend);

struct BenchCase {
  std::string sweep;  // particles, resolution, triangles, occlusion, latency
  const BenchMesh* mesh = nullptr;
  int width = 80, height = 60, particles = 0;
  OcclusionStorage mode = OcclusionStorage::PerPixelTime;
  // Each step's device time recorded (the split the sweeps print); off, the frame runs as a tracker's
  // does, without the timing records.
  bool step_timings = true;
  std::string test() const;  // e.g. "particles_handset_80x60_200p_per-pixel-time"; "_untimed" when so
};
// The cases of a grid: particles, resolution, occlusion and latency on the first mesh, triangles on each.
std::vector<BenchCase> grid_cases(const BenchGrid& grid, const std::vector<BenchMesh>& meshes);

// One case's outcome, for the rows and the figures.
struct CaseResult {
  BenchCase c;
  std::string backend;
  double frame_ms = 0, memory_mib = 0;
};

// Tracks the case's sequence on target and appends its rows (per step: time, bytes, GB/s; frame time,
// frames per second, latency (Tracker::update as its caller waits: the 640x480 frame's check and
// decimation too), device memory; speedup when reference_ms is finite). Error when it cannot run.
CaseResult run_case(const BenchCase& c, const BenchTarget& target, const std::string& renderer, int frames,
                    const std::string& commit, double reference_ms, std::vector<BenchRow>& rows);

}  // namespace depthtrack::cli
