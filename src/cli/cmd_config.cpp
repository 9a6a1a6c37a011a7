// depthtrack config: print every tracker parameter as the JSON that --config reads (--dump), or as a
// table of each key with its value, unit and meaning (--describe).
#include <algorithm>
#include <cstdio>
#include <depthtrack/config_file.hpp>
#include <depthtrack/error.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/tracker_config_fields.hpp"

namespace depthtrack::cli {

namespace {

struct ConfigArgs {
  std::string file;
  bool dump = false, describe = false;
};

struct KeyRow {
  std::string key, value, unit, meaning;
};

// A row per field of S under prefix, nested structs' fields after their own row; values from the JSON
// that --dump prints.
template <config_fields::Struct S>
void describe_fields(const nlohmann::ordered_json& values, const std::string& prefix, std::vector<KeyRow>& rows) {
  config_fields::for_each_field<S>([&](const auto& f) {
    using M = typename std::decay_t<decltype(f)>::member_type;
    const std::string key = prefix + f.name;
    if constexpr (config_fields::Struct<M>) {
      rows.push_back({key, "{...}", "", f.help});
      describe_fields<M>(values.at(f.name), key + ".", rows);
    } else {
      rows.push_back({key, values.at(f.name).dump(), f.unit, f.help});
    }
  });
}

std::string describe(const TrackerConfig& config, const std::string& file) {
  std::vector<KeyRow> rows{{"key", file.empty() ? "default" : "value", "unit", "meaning"}};
  describe_fields<TrackerConfig>(nlohmann::ordered_json::parse(tracker_config_to_json(config)), "", rows);
  size_t key = 0, value = 0, unit = 0;
  for (const KeyRow& r : rows) {
    key = std::max(key, r.key.size());
    value = std::max(value, r.value.size());
    unit = std::max(unit, r.unit.size());
  }
  std::string text;
  for (const KeyRow& r : rows) {
    text += r.key + std::string(key + 2 - r.key.size(), ' ') + r.value + std::string(value + 2 - r.value.size(), ' ') +
            r.unit + std::string(unit + 2 - r.unit.size(), ' ') + r.meaning + "\n";
  }
  return text;
}

}  // namespace

void add_config_command(CLI::App& app) {
  auto args = std::make_shared<ConfigArgs>();
  CLI::App* c = app.add_subcommand(
      "config",
      "Print every tracker parameter as JSON, the format of --config FILE on track and demo (--dump), or as a "
      "table of each key with its default, unit and meaning (--describe)");
  c->add_flag("--dump", args->dump,
              "Print the configuration as JSON: the defaults, or with --config FILE that file's with the defaults "
              "filled in (checked)");
  c->add_flag("--describe", args->describe,
              "Print a line per key (nested keys as observation.sigma_constant): its default (or its value in "
              "--config FILE), its unit (m: metres, s: seconds, ms, pixels, rad, Hz, probability, share: a "
              "fraction; blank: none) and what it means");
  c->add_option("--config", args->file, "JSON file to read (any subset of the parameters)")->check(CLI::ExistingFile);
  c->callback([args] {
    if (args->dump == args->describe) throw InputError("config: give one of --dump (JSON) and --describe (a table)");
    const TrackerConfig config = args->file.empty() ? TrackerConfig{} : load_tracker_config(args->file);
    std::fputs(args->dump ? tracker_config_to_json(config).c_str() : describe(config, args->file).c_str(), stdout);
  });
}

}  // namespace depthtrack::cli
