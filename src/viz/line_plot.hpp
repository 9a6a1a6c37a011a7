#pragma once
// Stacked line plots over a shared x axis (time), drawn with the built-in font: what
// `depthtrack plot` makes of a run's CSV.
#include <string>
#include <vector>

#include "viz/rgb_image.hpp"

namespace depthtrack::viz {

struct Series {
  std::string label;
  std::vector<double> y;  // one per x; NaN leaves a gap
  Rgb colour;
};

struct Panel {
  std::string title;
  std::vector<Series> series;
};

// Numbers at round steps (1, 2 or 5 times a power of ten) covering [low, high], about `count` of them.
std::vector<double> nice_ticks(double low, double high, int count = 5);

// One panel per entry, stacked, each with its own y axis (from 0, or the data's minimum if it is
// negative, to above the maximum), all sharing x. InputError when x is empty or a series' length
// differs from x's.
RgbImage plot_panels(const std::vector<double>& x, const std::string& x_label, const std::vector<Panel>& panels,
                     int width = 960, int panel_height = 200);

}  // namespace depthtrack::viz
