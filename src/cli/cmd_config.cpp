// depthtrack config: print every tracker parameter as the JSON that --config reads.
#include <cstdio>
#include <depthtrack/config_file.hpp>
#include <memory>
#include <string>

#include "cli/commands.hpp"

namespace depthtrack::cli {

void add_config_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  auto dump = std::make_shared<bool>(false);
  CLI::App* c = app.add_subcommand(
      "config", "Print every tracker parameter as JSON, the format of --config FILE on track and demo");
  c->add_flag("--dump", *dump,
              "Print the configuration: the defaults, or with --config FILE that file's with the defaults "
              "filled in (checked)")
      ->required();
  c->add_option("--config", *file, "JSON file to read (any subset of the parameters)")->check(CLI::ExistingFile);
  c->callback([file, dump] {
    static_cast<void>(dump);  // held by the callback: CLI11 writes the flag into it while parsing
    const TrackerConfig config = file->empty() ? TrackerConfig{} : load_tracker_config(*file);
    std::fputs(tracker_config_to_json(config).c_str(), stdout);
  });
}

}  // namespace depthtrack::cli
