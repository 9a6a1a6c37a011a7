// depthtrack plot: a PNG of a track run's CSV over time: errors, confidence, ESS and latency,
// each panel only when its column is there.
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/staged_outputs.hpp"
#include "viz/line_plot.hpp"

namespace depthtrack::cli {

namespace {

struct PlotArgs {
  std::string csv, out;
};

// The CSV's columns by name, every cell kept as text.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name) const {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  }
};

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the run CSV '" + path + "'");
  CsvTable table;
  std::string line;
  if (!std::getline(in, line) || line.empty()) throw InputError("'" + path + "' is empty: expected a header line");
  table.header = split_cells(line);
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    auto cells = split_cells(line);
    if (cells.size() != table.header.size())
      throw InputError("'" + path + "' line " + std::to_string(number) + " has " + std::to_string(cells.size()) +
                       " cells; the header has " + std::to_string(table.header.size()));
    table.rows.push_back(std::move(cells));
  }
  if (table.rows.empty()) throw InputError("'" + path + "' has a header but no rows");
  return table;
}

// A numeric column: empty or "nan" cells become NaN, anything else must be a number.
std::vector<double> numbers(const CsvTable& table, int column, const std::string& path) {
  std::vector<double> out;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::string& cell = table.rows[r][static_cast<size_t>(column)];
    if (cell.empty() || cell == "nan" || cell == "NaN") {
      out.push_back(NAN);
      continue;
    }
    size_t used = 0;
    double value = NAN;
    try {
      value = std::stod(cell, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != cell.size())
      throw InputError("'" + path + "' line " + std::to_string(r + 2) + ": column '" +
                       table.header[static_cast<size_t>(column)] + "' holds '" + cell + "', not a number");
    out.push_back(value);
  }
  return out;
}

// The rows of each object in order of first appearance; one unnamed object without an `object` column.
struct ObjectRows {
  std::vector<std::string> names;
  std::vector<std::vector<size_t>> rows;
};

ObjectRows rows_by_object(const CsvTable& table, const std::string& path) {
  ObjectRows out;
  const int column = table.column("object");
  if (column < 0) {
    out.names.emplace_back();
    out.rows.emplace_back();
    for (size_t r = 0; r < table.rows.size(); ++r) out.rows.front().push_back(r);
    return out;
  }
  std::map<std::string, size_t> index;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::string& name = table.rows[r][static_cast<size_t>(column)];
    const auto [it, added] = index.emplace(name, out.names.size());
    if (added) {
      out.names.push_back(name);
      out.rows.emplace_back();
    }
    out.rows[it->second].push_back(r);
  }
  // The series share one time axis: each object must have a row for each frame, at the same times.
  const int frame = table.column("frame");
  for (size_t o = 1; o < out.names.size(); ++o) {
    bool same = out.rows[o].size() == out.rows[0].size();
    for (size_t i = 0; same && frame >= 0 && i < out.rows[o].size(); ++i)
      same = table.rows[out.rows[o][i]][static_cast<size_t>(frame)] ==
             table.rows[out.rows[0][i]][static_cast<size_t>(frame)];
    if (!same)
      throw InputError("'" + path + "': object '" + out.names[o] + "' has other frames than '" + out.names[0] + "' (" +
                       std::to_string(out.rows[o].size()) + " rows against " + std::to_string(out.rows[0].size()) +
                       "): plot draws objects tracked over the same frames");
  }
  return out;
}

void run_plot(const PlotArgs& a) {
  StagedOutputs outputs;
  outputs.add_input(a.csv);
  const std::filesystem::path png = outputs.add("--out", a.out);
  const CsvTable table = read_csv(a.csv);
  struct Wanted {
    const char *column, *label;
    viz::Rgb colour;
  };
  struct PanelSpec {
    const char* title;
    std::vector<Wanted> series;
  };
  const PanelSpec specs[] = {
      {"TRANSLATION ERROR (MM)", {{"err_t_mm", "CENTRE", {200, 40, 40}}, {"adds_mm", "ADD-S", {40, 90, 200}}}},
      {"ROTATION ERROR (DEG)", {{"err_r_deg", "ROTATION", {200, 40, 40}}}},
      {"CONFIDENCE", {{"confidence", "CONFIDENCE", {20, 140, 60}}}},
      {"EFFECTIVE SAMPLE SIZE", {{"ess", "ESS", {120, 60, 170}}}},
      {"LATENCY (MS)", {{"latency_ms", "LATENCY", {210, 120, 0}}}},
  };
  // Several objects (track with --mesh/--object pairs, an `object` column): a series per object over
  // the frames, rather than their rows joined into one saw-tooth line.
  const ObjectRows objects = rows_by_object(table, a.csv);
  const viz::Rgb palette[] = {{200, 40, 40},  {40, 90, 200}, {20, 140, 60},
                              {120, 60, 170}, {210, 120, 0}, {0, 150, 160}};
  std::vector<viz::Panel> panels;
  for (const PanelSpec& spec : specs) {
    viz::Panel panel{spec.title, {}};
    for (const Wanted& w : spec.series) {
      const int c = table.column(w.column);
      if (c < 0) continue;
      const std::vector<double> values = numbers(table, c, a.csv);
      if (objects.names.size() == 1) {
        panel.series.push_back({w.label, values, w.colour});
        continue;
      }
      for (size_t o = 0; o < objects.names.size(); ++o) {
        std::vector<double> y;
        for (const size_t row : objects.rows[o]) y.push_back(values[row]);
        const std::string label = (spec.series.size() > 1 ? std::string(w.label) + " " : "") + objects.names[o];
        panel.series.push_back({label, y, palette[(o + (&w - spec.series.data()) * 3) % std::size(palette)]});
      }
    }
    if (!panel.series.empty()) panels.push_back(std::move(panel));
  }
  if (panels.empty())
    throw InputError("'" + a.csv +
                     "' has none of the columns plot shows (err_t_mm, adds_mm, err_r_deg, confidence, ess, "
                     "latency_ms): is it a track CSV?");
  const int time = table.column("timestamp");
  std::vector<double> x;
  if (time >= 0) {
    const std::vector<double> times = numbers(table, time, a.csv);
    for (const size_t row : objects.rows.front()) x.push_back(times[row]);
  } else {
    for (size_t i = 0; i < objects.rows.front().size(); ++i) x.push_back(static_cast<double>(i));
  }
  viz::plot_panels(x, time >= 0 ? "TIME (S)" : "FRAME", panels).save_png(png);
  outputs.commit();
  std::printf("wrote %s: %zu panel%s, %zu frames", a.out.c_str(), panels.size(), panels.size() == 1 ? "" : "s",
              x.size());
  if (objects.names.size() > 1) std::printf(", %zu objects", objects.names.size());
  std::printf("\n");
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto args = std::make_shared<PlotArgs>();
  CLI::App* c = app.add_subcommand(
      "plot",
      "Draw a track run's CSV as a PNG over time: translation error and ADD-S, rotation error, confidence, ESS "
      "and latency, each panel when its column is present");
  c->add_option("csv", args->csv, "The CSV that `depthtrack track --out` wrote")->required();
  c->add_option("--out", args->out, "PNG to write")->required();
  c->callback([args] { run_plot(*args); });
}

}  // namespace depthtrack::cli
