#pragma once
// Each subcommand of the depthtrack command registers itself on the CLI11 app.
#include <CLI/CLI.hpp>

namespace depthtrack::cli {

void add_demo_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_track_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_plot_command(CLI::App& app);
void add_config_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_eval_command(CLI::App& app);

}  // namespace depthtrack::cli
