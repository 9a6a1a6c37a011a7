// The JSON configuration file: every TrackerConfig field, round trips, errors naming the key, and
// `depthtrack config --dump` / `--config FILE` on the command line.
#include <catch2/catch.hpp>
#include <cstddef>
#include <depthtrack/config_file.hpp>
#include <depthtrack/error.hpp>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>

#include "core/tracker_config_fields.hpp"
#include "support.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;
namespace fields = depthtrack::config_fields;

namespace {

// Gives every field of s a value unlike its default (and unlike the others'), nested too.
template <typename S>
void change_every_field(S& s, int& counter) {
  fields::for_each_field<S>([&](const auto& f) {
    using M = typename std::decay_t<decltype(f)>::member_type;
    auto& m = s.*f.member;
    ++counter;
    if constexpr (fields::Struct<M>)
      change_every_field(m, counter);
    else if constexpr (std::is_same_v<M, bool>)
      m = !m;
    else if constexpr (std::is_same_v<M, OcclusionStorage>)
      m = OcclusionStorage::GlobalTime;
    else if constexpr (std::is_same_v<M, Renderer>)
      m = Renderer::Gl;
    else if constexpr (std::is_same_v<M, RefineLayout>)
      m = RefineLayout::Spread;
    else if constexpr (std::is_same_v<M, std::string>)
      m = "value-" + std::to_string(counter);
    else if constexpr (std::is_same_v<M, double>)
      m = m * 0.5 + 1e-3 * counter;
    else
      m = m + static_cast<M>(counter);
  });
}

// Byte ranges [offset, offset + size) of S's listed fields, nested structs as one range each.
template <typename S>
std::map<size_t, size_t> listed_ranges(const S& s) {
  std::map<size_t, size_t> ranges;
  fields::for_each_field<S>([&](const auto& f) {
    const auto* base = reinterpret_cast<const unsigned char*>(&s);
    const auto* member = reinterpret_cast<const unsigned char*>(&(s.*f.member));
    ranges[static_cast<size_t>(member - base)] = sizeof(s.*f.member);
  });
  return ranges;
}

// Every byte of S lies in a listed field, but for padding (shorter than the next field's alignment):
// a field declared in tracker_config.hpp but missing from the list leaves a gap.
template <typename S>
void require_every_field_listed(const char* name) {
  const S s{};
  size_t end = 0;
  for (const auto& [offset, size] : listed_ranges(s)) {
    INFO(name << ": bytes " << end << " to " << offset << " hold no listed field (core/tracker_config_fields.hpp)");
    REQUIRE(offset - end < alignof(std::max_align_t));
    REQUIRE(offset >= end);
    end = offset + size;
  }
  INFO(name << ": bytes after " << end << " of " << sizeof(S) << " hold no listed field");
  REQUIRE(sizeof(S) - end < alignof(S));
  fields::for_each_field<S>([&](const auto& f) {
    using M = typename std::decay_t<decltype(f)>::member_type;
    if constexpr (fields::Struct<M>) require_every_field_listed<M>(f.name);
  });
}

}  // namespace

TEST_CASE("The field list covers every byte of TrackerConfig and its parts", "[config]") {
  require_every_field_listed<TrackerConfig>("TrackerConfig");
}

TEST_CASE("Configuration JSON round-trips: the defaults and every field changed", "[config]") {
  const TrackerConfig defaults;
  CHECK(same_config(tracker_config_from_json(tracker_config_to_json(defaults)), defaults));
  TrackerConfig changed;
  int counter = 0;
  change_every_field(changed, counter);
  CHECK(counter >= 39);                      // 16 top-level entries and 23 nested ones
  changed.occlusion.p_occluded_stays = 0.6;  // values validate() accepts where the generic change would not
  changed.occlusion.p_visible_to_occluded = 0.2;
  changed.motion.damping = 0.7;
  changed.backend = "reference";
  changed.renderer = Renderer::Gl;
  changed.gl_path = "osmesa";
  changed.width = 160;
  changed.loss.lost_below = 0.2;
  changed.loss.found_above = 0.9;
  changed.loss.found_outline = 0.4;
  changed.refine.min_incidence = 0.2;
  changed.observation.tail_weight = 0.02;
  changed.occlusion.initial = 0.3;
  REQUIRE_NOTHROW(changed.validate());
  const std::string text = tracker_config_to_json(changed);
  const TrackerConfig loaded = tracker_config_from_json(text);
  CHECK(same_config(loaded, changed));
  CHECK(!same_config(loaded, defaults));
  // Each field on its own makes a difference to same_config: it compares them all.
  fields::for_each_field<TrackerConfig>([&](const auto& f) {
    TrackerConfig one = defaults;
    one.*f.member = changed.*f.member;
    INFO(f.name);
    CHECK(!same_config(one, defaults));
  });
}

TEST_CASE("The dumped defaults hold the documented values, nested as in TrackerConfig", "[config]") {
  const auto j = nlohmann::json::parse(tracker_config_to_json(TrackerConfig{}));
  CHECK(j["particles"] == 200);
  CHECK(j["width"] == 80);
  CHECK(j["height"] == 60);
  CHECK(j["seed"] == 1);
  CHECK(j["backend"] == "");
  CHECK(j["renderer"] == "kernel");
  CHECK(j["occlusion_storage"] == "per-pixel-time");
  CHECK(j["observation"]["sigma_constant"] == 0.003);
  CHECK(j["observation"]["occluder_rate"] == std::log(2.0));
  CHECK(j["refine"]["iterations"] == 8);
  CHECK(j["refine"]["enabled"] == true);
  CHECK(j["recovery"]["budget_ms"] == 500);
  CHECK(j["loss"]["search_after"] == 3);
}

TEST_CASE("A partial file overrides only its keys; bad keys, types and values name the field", "[config]") {
  const TrackerConfig c = tracker_config_from_json(R"({"particles": 50, "observation": {"max_depth": 3.5},
                                                      "occlusion_storage": "off", "refine": {"enabled": false}})");
  CHECK(c.particles == 50);
  CHECK(c.observation.max_depth == 3.5);
  CHECK(c.observation.sigma_constant == 0.003);
  CHECK(c.occlusion_storage == OcclusionStorage::Off);
  CHECK(!c.refine.enabled);
  CHECK(c.refine.iterations == 8);

  CHECK_THROWS_WITH(tracker_config_from_json(R"({"particle": 5})", {}, "f.json"),
                    Contains("f.json: unknown key 'particle'"));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"observation": {"sigma_constnt": 0.1}})"),
                    Contains("unknown key 'observation.sigma_constnt'"));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"observation": {"sigma_constant": "0.1"}})"),
                    Contains("'observation.sigma_constant' must be a number, got a string \"0.1\""));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"particles": 2.5})"),
                    Contains("'particles' must be an integer, got a number 2.5"));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"particles": 1e12})"), Contains("'particles' must be an integer"));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"seed": -1})"), Contains("'seed' must be a non-negative integer"));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"refine": {"enabled": 1}})"),
                    Contains("'refine.enabled' must be true or false"));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"motion": 3})"), Contains("'motion' must be an object"));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"occlusion_storage": "sometimes"})"),
                    Contains("'occlusion_storage': unknown occlusion mode 'sometimes'"));
  CHECK_THROWS_WITH(
      tracker_config_from_json(R"({"refine": {"layout": "many"}})"),
      Contains("'refine.layout': unknown refinement layout 'many' (choose auto, one-group, spread or one-launch)"));
  CHECK(tracker_config_from_json(R"({"refine": {"layout": "one-group"}})").refine.layout == RefineLayout::OneGroup);
  CHECK_THROWS_WITH(tracker_config_from_json(R"([1, 2])"), Contains("must be an object, got an array"));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"particles": 0})"), Contains("particle count 0 must be at least 1"));
  CHECK_THROWS_WITH(tracker_config_from_json(R"({"atlas_particles": -3})"),
                    Contains("atlas particles -3 must not be negative"));
  CHECK(tracker_config_from_json(R"({"atlas_particles": 500})").atlas_particles == 500);
  CHECK_THROWS_WITH(tracker_config_from_json("{\"particles\": 5,"), Contains("not valid JSON"));
  CHECK_THROWS_WITH(load_tracker_config("/nonexistent/c.json"),
                    Contains("cannot open configuration file '/nonexistent/c.json'"));
}

TEST_CASE("depthtrack config --dump prints what --config reads; flags override the file", "[config][cli]") {
  const auto dir = test::temp_dir("config_cli");
  const auto [rc, dumped] = test::run_cli("config --dump", dir / "dump.log");
  REQUIRE(rc == 0);
  CHECK(same_config(tracker_config_from_json(dumped), TrackerConfig{}));

  std::ofstream(dir / "c.json") << R"({"particles": 40, "width": 40, "height": 30, "seed": 9,
                                      "refine": {"iterations": 2}, "recovery": {"enabled": false}})";
  const auto [rc2, text] = test::run_cli("config --dump --config " + (dir / "c.json").string(), dir / "c.log");
  REQUIRE(rc2 == 0);
  const TrackerConfig full = tracker_config_from_json(text);
  CHECK(full.particles == 40);
  CHECK(full.width == 40);
  CHECK(full.refine.iterations == 2);
  CHECK(!full.recovery.enabled);
  CHECK(full.observation.max_depth == 6.0);

  // demo prints the particle count and resolution it tracks with: from the file, then a flag over it.
  const auto [rc3, demo] = test::run_cli("demo --frames 2 --config " + (dir / "c.json").string(), dir / "d.log");
  REQUIRE(rc3 == 0);
  CHECK_THAT(demo, Contains("tracked at 40x30 with 40 particles"));
  const auto [rc4, flagged] =
      test::run_cli("demo --frames 2 --particles 30 --config " + (dir / "c.json").string(), dir / "f.log");
  REQUIRE(rc4 == 0);
  CHECK_THAT(flagged, Contains("tracked at 40x30 with 30 particles"));

  std::ofstream(dir / "bad.json") << R"({"loss": {"lost_aftr": 2}})";
  const auto [rc5, bad] = test::run_cli("demo --frames 2 --config " + (dir / "bad.json").string(), dir / "b.log");
  CHECK(rc5 == 1);
  CHECK_THAT(bad, Contains("unknown key 'loss.lost_aftr'"));
  CHECK_THAT(bad, Contains("bad.json"));
}
