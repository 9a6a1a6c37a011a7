// depthtrack plot: a PNG of a track run's CSV over time, drawn by depthtrack/plots.py (matplotlib):
// errors, confidence, ESS and latency, each panel when its column is there, a line per object; or, with
// --timeline, error and confidence over the run with the lost frames shaded.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/python_plots.hpp"
#include "cli/staged_outputs.hpp"

namespace depthtrack::cli {

namespace {

struct PlotArgs {
  std::string csv, out;
  bool timeline = false;
};

void run_plot(const PlotArgs& a) {
  const PlotRunner runner = find_plot_runner("plot");
  StagedOutputs outputs;
  outputs.add_input(a.csv);
  const std::filesystem::path png = outputs.add("--out", a.out);
  const std::string drawn = run_plots(runner, {a.timeline ? "timeline" : "run", a.csv, png.string()});
  outputs.commit();
  std::printf("wrote %s: %s\n", a.out.c_str(), drawn.c_str());
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto args = std::make_shared<PlotArgs>();
  CLI::App* c = app.add_subcommand(
      "plot",
      "Draw a track run's CSV as a PNG over time (python3 with matplotlib draws it): translation error and "
      "ADD-S (mm), rotation error (deg), confidence, ESS and latency (ms), each panel when its column is "
      "present, a line per object");
  c->add_option("csv", args->csv, "The CSV that `depthtrack track --out` wrote")->required();
  c->add_option("--out", args->out, "PNG to write")->required();
  c->add_flag("--timeline", args->timeline,
              "Draw instead the error (ADD-S, else the centre error, in mm) and the confidence over the run, a "
              "row per object, the frames it was lost shaded");
  c->callback([args] { run_plot(*args); });
}

}  // namespace depthtrack::cli
