#include "viz/line_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>

#include "viz/bitmap_font.hpp"

namespace depthtrack::viz {

namespace {
constexpr int kScale = 2;  // font scale: 10x14 px letters
constexpr int kLeft = 90, kRight = 36, kTop = 34, kBottom = 14, kAxisLabel = 56;
constexpr Rgb kInk{30, 30, 30}, kGrid{225, 225, 225}, kPaper{255, 255, 255};

std::string tick_label(double value, double step) {
  char text[32];
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  std::snprintf(text, sizeof text, "%.*f", decimals, std::abs(value) < step * 1e-6 ? 0.0 : value);
  return text;
}

struct Range {
  double low, high;
};

Range y_range(const Panel& panel) {
  double low = 0, high = 0;
  for (const Series& s : panel.series)
    for (double y : s.y)
      if (std::isfinite(y)) {
        low = std::min(low, y);
        high = std::max(high, y);
      }
  if (high <= low) high = low + 1;  // flat or empty: still an axis
  return {low, high + 0.05 * (high - low)};
}
}  // namespace

std::vector<double> nice_ticks(double low, double high, int count) {
  if (!(high > low) || count < 1) return {low};
  const double raw = (high - low) / count, power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(low / step - 1e-9) * step; t <= high + step * 1e-9; t += step) ticks.push_back(t);
  return ticks;
}

RgbImage plot_panels(const std::vector<double>& x, const std::string& x_label, const std::vector<Panel>& panels,
                     int width, int panel_height) {
  if (x.empty()) throw InputError("nothing to plot: no rows");
  if (panels.empty()) throw InputError("nothing to plot: no columns to show");
  for (const Panel& p : panels)
    for (const Series& s : p.series)
      if (s.y.size() != x.size())
        throw InputError("series '" + s.label + "' has " + std::to_string(s.y.size()) + " values for " +
                         std::to_string(x.size()) + " x values");
  const int height = static_cast<int>(panels.size()) * panel_height + kAxisLabel;
  RgbImage image(width, height, kPaper);
  const auto [x_min, x_max_raw] = std::minmax_element(x.begin(), x.end());
  const double x0 = *x_min, x1 = *x_max_raw > x0 ? *x_max_raw : x0 + 1;
  const int plot_left = kLeft, plot_right = width - kRight;
  auto to_px = [&](double value) { return plot_left + (value - x0) / (x1 - x0) * (plot_right - plot_left); };
  const std::vector<double> x_ticks = nice_ticks(x0, x1, 6);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1;

  for (size_t k = 0; k < panels.size(); ++k) {
    const Panel& panel = panels[k];
    const int top = static_cast<int>(k) * panel_height + kTop,
              bottom = static_cast<int>(k + 1) * panel_height - kBottom;
    const Range r = y_range(panel);
    auto to_py = [&](double value) { return bottom - (value - r.low) / (r.high - r.low) * (bottom - top); };
    // Grid and tick labels.
    const std::vector<double> y_ticks = nice_ticks(r.low, r.high, 4);
    const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1;
    for (double t : y_ticks) {
      const int py = static_cast<int>(std::lround(to_py(t)));
      image.line(plot_left, py, plot_right, py, kGrid);
      const std::string label = tick_label(t, y_step);
      draw_text(image, plot_left - 8 - text_width(label, kScale), py - text_height(kScale) / 2, label, kInk, kScale);
    }
    for (double t : x_ticks) {
      const int px = static_cast<int>(std::lround(to_px(t)));
      image.line(px, top, px, bottom, kGrid);
    }
    image.line(plot_left, top, plot_left, bottom, kInk);
    image.line(plot_left, bottom, plot_right, bottom, kInk);
    draw_text(image, plot_left, top - text_height(kScale) - 8, panel.title, kInk, kScale);
    // Legend at the top right, in the series' colours.
    int legend_right = plot_right;
    for (auto s = panel.series.rbegin(); s != panel.series.rend(); ++s) {
      legend_right -= text_width(s->label, kScale);
      draw_text(image, legend_right, top - text_height(kScale) - 8, s->label, s->colour, kScale);
      legend_right -= 24;
    }
    // The lines; a single point between gaps is drawn as a dot.
    for (const Series& s : panel.series)
      for (size_t i = 0; i < x.size(); ++i) {
        if (!std::isfinite(s.y[i])) continue;
        const bool next = i + 1 < x.size() && std::isfinite(s.y[i + 1]);
        const size_t j = next ? i + 1 : i;
        image.line(to_px(x[i]), to_py(s.y[i]), to_px(x[j]), to_py(s.y[j]), s.colour, 2);
      }
  }
  // The shared x axis under the last panel.
  const int axis_y = static_cast<int>(panels.size()) * panel_height - kBottom + 14;  // below the lowest y label
  for (double t : x_ticks) {
    const std::string label = tick_label(t, x_step);
    const int left = static_cast<int>(std::lround(to_px(t))) - text_width(label, kScale) / 2;
    draw_text(image, std::clamp(left, 0, width - text_width(label, kScale)), axis_y, label, kInk, kScale);
  }
  draw_text(image, (plot_left + plot_right - text_width(x_label, kScale)) / 2, axis_y + text_height(kScale) + 8,
            x_label, kInk, kScale);
  return image;
}

}  // namespace depthtrack::viz
