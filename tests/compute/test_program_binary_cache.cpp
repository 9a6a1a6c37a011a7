// The on-disk cache of compiled programs (compute/program_binary_cache.hpp): what it stores comes
// back only for the same key and only from an intact file, and where it lives; on the test device
// (OpenCL or CUDA) a second Tracker loads every program from it and tracks exactly as a compiled one,
// and a corrupt entry is rebuilt and replaced. OpenCL's refused binaries, an unwritable folder and the
// switch: test_compute_opencl_binary_cache.cpp.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <depthtrack/device.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include "binary_cache_support.hpp"
#include "compute/program_binary_cache.hpp"
#include "compute/program_cache.hpp"
#include "device_support.hpp"
#include "folded_programs.hpp"
#include "support.hpp"
#include "synth_frames.hpp"
#include "tracker/device_access.hpp"

using namespace depthtrack;
namespace fs = std::filesystem;
using compute::ProgramBinaryCache;
using test::ScopedEnv, test::read_all, test::write_all, test::files_in;

TEST_CASE("the program binary cache gives back what was stored under the same key from an intact file only",
          "[compute][cache]") {
  const auto dir = test::temp_dir("binary_cache_store");
  const ProgramBinaryCache cache(dir / "programs");
  CHECK_FALSE(cache.load("key a"));  // nothing stored yet, not even the folder
  const std::string binary(
      "\x7f"
      "ELF\0binary\0bytes",
      17);
  REQUIRE(cache.store("key a", binary));
  CHECK(cache.load("key a") == binary);
  CHECK_FALSE(cache.load("key b"));
  CHECK(files_in(dir / "programs") == 1);  // no temporary file left behind

  // Another key's file under this key's name (a hash collision) is a miss: the file repeats its key.
  fs::copy_file(cache.path_of("key a"), cache.path_of("key b"));
  CHECK_FALSE(cache.load("key b"));

  const std::string intact = read_all(cache.path_of("key a"));
  std::string flipped = intact;
  flipped[intact.size() - 12] ^= 0x20;  // a byte of the binary: the checksum disagrees
  write_all(cache.path_of("key a"), flipped);
  CHECK_FALSE(cache.load("key a"));
  write_all(cache.path_of("key a"), intact.substr(0, intact.size() - 3));  // truncated
  CHECK_FALSE(cache.load("key a"));
  write_all(cache.path_of("key a"), intact + "x");  // trailing bytes
  CHECK_FALSE(cache.load("key a"));
  write_all(cache.path_of("key a"), "");
  CHECK_FALSE(cache.load("key a"));
  REQUIRE(cache.store("key a", binary));  // stored again over the corrupt file
  CHECK(cache.load("key a") == binary);

  // A folder that cannot be made (a file is in the way) is a failed store, not an error.
  write_all(dir / "blocker", "a file");
  const ProgramBinaryCache unwritable(dir / "blocker" / "programs");
  CHECK_FALSE(unwritable.store("key a", binary));
  CHECK_FALSE(unwritable.load("key a"));
}

TEST_CASE("the program binary cache's folder comes from XDG_CACHE_HOME or HOME, and off turns it off",
          "[compute][cache]") {
  const ScopedEnv on("DEPTHTRACK_PROGRAM_CACHE", nullptr);
  {
    const ScopedEnv xdg("XDG_CACHE_HOME", "/somewhere/cache");
    REQUIRE(ProgramBinaryCache::from_environment());
    CHECK(ProgramBinaryCache::from_environment()->folder() == fs::path("/somewhere/cache/depthtrack/programs"));
    const ScopedEnv off("DEPTHTRACK_PROGRAM_CACHE", "off");
    CHECK_FALSE(ProgramBinaryCache::from_environment());
  }
  const ScopedEnv no_xdg("XDG_CACHE_HOME", nullptr);
  {
    const ScopedEnv home("HOME", "/home/someone");
    REQUIRE(ProgramBinaryCache::from_environment());
    CHECK(ProgramBinaryCache::from_environment()->folder() == fs::path("/home/someone/.cache/depthtrack/programs"));
  }
  const ScopedEnv no_home("HOME", nullptr);
  CHECK_FALSE(ProgramBinaryCache::from_environment());
}

TEST_CASE("a second Tracker loads every program from the binary cache and tracks exactly as the first",
          "[compute][cache][device]") {
  if (!test::device_available()) return;
  const auto dir = test::temp_dir("binary_cache_tracker");
  const ScopedEnv on("DEPTHTRACK_PROGRAM_CACHE", nullptr);
  const ScopedEnv xdg("XDG_CACHE_HOME", dir.c_str());
  const fs::path folder = dir / "depthtrack" / "programs";
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth;
  synth.camera = synth.camera.decimated(8);
  synth.frames = 2;
  const auto frames = test::synthesize(mesh, synth);
  TrackerConfig config;
  config.backend = test::device_selector();
  config.particles = 64;

  const auto compiled_device = Device::open(config.backend);
  Tracker compiled(compiled_device, mesh, synth.camera, config);
  const auto& compiled_programs = DeviceAccess::context(*compiled_device)->programs;
  // Nine programs but those whose work is folded into others here (test::programs_folded_away).
  const size_t programs =
      9 - test::programs_folded_away(*DeviceAccess::context(*compiled_device)->queue, mesh, synth.camera, config);
  REQUIRE(compiled_programs.builds() == programs);
  CHECK(compiled_programs.loaded_from_disk() == 0);
  REQUIRE(files_in(folder) == programs);

  const auto loaded_device = Device::open(config.backend);
  Tracker loaded(loaded_device, mesh, synth.camera, config);
  CHECK(DeviceAccess::context(*loaded_device)->programs.builds() == programs);
  CHECK(DeviceAccess::context(*loaded_device)->programs.loaded_from_disk() == programs);
  compiled.initialize(frames[0].ground_truth);
  loaded.initialize(frames[0].ground_truth);
  for (const auto& f : frames) {
    const Estimate a = compiled.update(f.depth, f.timestamp), b = loaded.update(f.depth, f.timestamp);
    REQUIRE(a.pose.translation == b.pose.translation);
    REQUIRE(a.pose.rotation.coeffs() == b.pose.rotation.coeffs());
    REQUIRE(a.effective_sample_size == b.effective_sample_size);
  }

  // A corrupt entry is a miss: that program is compiled again and its entry replaced.
  const fs::path victim = fs::directory_iterator(folder)->path();
  std::string bytes = read_all(victim);
  bytes[bytes.size() / 2] ^= 0x55;
  write_all(victim, bytes);
  const auto repaired_device = Device::open(config.backend);
  Tracker repaired(repaired_device, mesh, synth.camera, config);
  CHECK(DeviceAccess::context(*repaired_device)->programs.loaded_from_disk() == programs - 1);
  CHECK(read_all(victim) != bytes);
  CHECK(files_in(folder) == programs);
  const auto again = Device::open(config.backend);
  Tracker after_repair(again, mesh, synth.camera, config);
  CHECK(DeviceAccess::context(*again)->programs.loaded_from_disk() == programs);
}
