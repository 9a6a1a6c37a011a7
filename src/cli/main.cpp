// depthtrack: track a known object through depth images (see --help of each subcommand).
#include <depthtrack/error.hpp>
#include <exception>
#include <iostream>

#include "cli/commands.hpp"
#include "core/partial_files.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "depthtrack: 6-DoF tracking of a known rigid object in depth images with an occlusion-aware particle filter"};
  app.set_version_flag("--version", "depthtrack " DEPTHTRACK_VERSION);
  app.require_subcommand(1);
  depthtrack::cli::add_demo_command(app);
  depthtrack::cli::add_synth_command(app);
  depthtrack::cli::add_track_command(app);
  depthtrack::cli::add_info_command(app);
  depthtrack::cli::add_plot_command(app);
  depthtrack::cli::add_config_command(app);
  depthtrack::cli::add_bench_command(app);
  depthtrack::cli::add_eval_command(app);
  // Ctrl-C or a kill leaves no partial output behind (earlier outputs are replaced only on success).
  depthtrack::remove_partial_files_on_interrupt();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const depthtrack::Error& e) {
    std::cerr << "depthtrack: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "depthtrack: unexpected error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
