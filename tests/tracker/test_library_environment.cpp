// The library reads no environment: DEPTHTRACK_DEVICE and DEPTHTRACK_GL set to garbage in this process change
// nothing for a Tracker built from an explicit configuration. The command still reads them, as its defaults.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "device_support.hpp"
#include "scene.hpp"
#include "support.hpp"

using namespace depthtrack;

namespace {
const Camera sensor = Camera::make(160, 120, 131.25, 131.25, 79.875, 59.875);
const Pose truth({0.0, 0.0, 0.8}, Eigen::Quaterniond::Identity());

// Sets the two variables to nonsense for one scope, restoring what was there.
class GarbageEnvironment {
 public:
  GarbageEnvironment() {
    for (const char* name : {"DEPTHTRACK_DEVICE", "DEPTHTRACK_GL"}) {
      const char* old = std::getenv(name);
      saved_.push_back({name, old ? std::optional<std::string>(old) : std::nullopt});
      setenv(name, "quantum-nonsense", 1);
    }
  }
  ~GarbageEnvironment() {
    for (const auto& [name, old] : saved_) old ? setenv(name, old->c_str(), 1) : unsetenv(name);
  }

 private:
  std::vector<std::pair<const char*, std::optional<std::string>>> saved_;
};

void tracks_one_frame(const TrackerConfig& config) {
  Tracker tracker(builtin_demo_mesh(), sensor, config);
  tracker.initialize(truth);
  const Estimate estimate = tracker.update(test::render_scene(builtin_demo_mesh(), sensor, truth), 0.0);
  CHECK((estimate.pose.translation - truth.translation).norm() < 0.05);
}
}  // namespace

TEST_CASE("the library ignores DEPTHTRACK_DEVICE and DEPTHTRACK_GL", "[errors][environment]") {
  const GarbageEnvironment garbage;
  // An empty backend is the reference, whatever the environment says (it used to be DEPTHTRACK_DEVICE's).
  CHECK(TrackerConfig{}.resolved_backend() == "reference");
  TrackerConfig config;
  config.particles = 50;
  tracks_one_frame(config);
  if (!test::device_available()) return;
  config.backend = test::device_selector();
  tracks_one_frame(config);
  // The GL renderer's path comes from gl_path ("auto"), not DEPTHTRACK_GL (which once stopped it here).
  if (!test::gl_built()) return;
  config.renderer = Renderer::Gl;
  try {
    tracks_one_frame(config);
  } catch (const BackendError& e) {
    std::cout << "SKIPPED: no headless GL path: " << e.what() << "\n";
  }
}

TEST_CASE("a GL path the configuration names is checked", "[errors][environment]") {
  TrackerConfig config;
  config.gl_path = "quantum";
  CHECK_THROWS_WITH(config.validate(), Catch::Contains("GL path 'quantum'") && Catch::Contains("egl-surfaceless"));
  for (const char* path : {"auto", "egl-device", "egl-surfaceless", "osmesa"}) {
    config.gl_path = path;
    CHECK_NOTHROW(config.validate());
  }
}

TEST_CASE("the command still takes its defaults from DEPTHTRACK_DEVICE and DEPTHTRACK_GL", "[cli][environment]") {
  const auto dir = test::temp_dir("cli_environment");
  {
    const auto [status, output] = test::run_cli("demo --frames 1", dir / "device.txt", "DEPTHTRACK_DEVICE=quantum");
    INFO(output);
    CHECK(status == 1);
    CHECK(output.find("'quantum'") != std::string::npos);
  }
  {  // --backend wins over the environment
    const auto [status, output] = test::run_cli("demo --frames 1 --particles 20 --backend reference", dir / "flag.txt",
                                                "DEPTHTRACK_DEVICE=quantum");
    INFO(output);
    CHECK(status == 0);
  }
  {  // the GL path is checked whether it came from --gl or the environment
    const auto [status, output] = test::run_cli("demo --frames 1 --gl quantum", dir / "gl_flag.txt");
    INFO(output);
    CHECK(status == 1);
    CHECK(output.find("GL path 'quantum'") != std::string::npos);
    const auto [env_status, env_output] = test::run_cli("demo --frames 1", dir / "gl_env.txt", "DEPTHTRACK_GL=quantum");
    INFO(env_output);
    CHECK(env_status == 1);
    CHECK(env_output.find("GL path 'quantum'") != std::string::npos);
  }
}
