#include "viz/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <depthtrack/error.hpp>

#include "viz/bitmap_font.hpp"

namespace depthtrack::viz {

namespace {
// A depth step between neighbouring covered pixels that counts as an edge of the shape: 1 cm plus
// 2 % of the depth, above what a slanted surface gives between neighbours at these distances.
double depth_edge_threshold(double z) {
  return 0.01 + 0.02 * z;
}

Rgb lerp(Rgb a, Rgb b, double t) {
  auto mix = [t](uint8_t x, uint8_t y) { return static_cast<uint8_t>(std::lround((1 - t) * x + t * y)); };
  return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

constexpr Rgb kInside{0, 230, 0}, kOutline{60, 255, 60}, kDepthEdge{255, 0, 255}, kText{255, 255, 255};
}  // namespace

RgbImage colour_mapped_depth(const DepthImage& depth) {
  RgbImage image(depth.width(), depth.height());
  std::vector<float> valid;
  for (float z : depth.data())
    if (DepthImage::is_valid(z)) valid.push_back(z);
  if (valid.empty()) return image;
  std::sort(valid.begin(), valid.end());
  const double near = valid[valid.size() / 1000], far = valid[valid.size() * 999 / 1000];
  const Rgb stops[] = {{255, 235, 190}, {90, 150, 210}, {15, 25, 80}};
  for (int v = 0; v < depth.height(); ++v)
    for (int u = 0; u < depth.width(); ++u) {
      const float z = depth.at(u, v);
      if (!DepthImage::is_valid(z)) continue;
      const double t = far > near ? std::clamp((z - near) / (far - near), 0.0, 1.0) : 0.0;
      image.set(u, v, t < 0.5 ? lerp(stops[0], stops[1], 2 * t) : lerp(stops[1], stops[2], 2 * t - 1));
    }
  return image;
}

OverlayPainter::OverlayPainter(const Mesh& mesh, const Camera& sensor)
    : rasterizer_(mesh, sensor, 0.05, 100.0), sensor_(sensor) {}

std::vector<OverlayMark> OverlayPainter::marks(const Pose& camera_from_object) const {
  const int w = sensor_.width, h = sensor_.height;
  std::vector<float> depth(static_cast<size_t>(sensor_.pixel_count()), 0.0f);
  rasterizer_.render(camera_from_object, depth);
  std::vector<OverlayMark> out(depth.size(), OverlayMark::None);
  auto at = [&](int u, int v) {
    return depth[static_cast<size_t>(v) * static_cast<size_t>(w) + static_cast<size_t>(u)];
  };
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const float z = at(u, v);
      if (z <= 0) continue;
      OverlayMark mark = OverlayMark::Inside;
      const int neighbours[4][2] = {{u - 1, v}, {u + 1, v}, {u, v - 1}, {u, v + 1}};
      for (const auto& [nu, nv] : neighbours) {
        const float n = (nu < 0 || nv < 0 || nu >= w || nv >= h) ? 0.0f : at(nu, nv);
        if (n <= 0) {
          mark = OverlayMark::Outline;
          break;
        }
        // Only the nearer side of a step is marked, so an edge is one pixel wide.
        if (n - z > depth_edge_threshold(z)) mark = OverlayMark::DepthEdge;
      }
      out[static_cast<size_t>(v) * static_cast<size_t>(w) + static_cast<size_t>(u)] = mark;
    }
  return out;
}

RgbImage OverlayPainter::paint(const RgbImage& background, const Pose& camera_from_object,
                               const std::vector<std::string>& text) const {
  if (background.width() != sensor_.width || background.height() != sensor_.height)
    throw InputError("overlay background is " + std::to_string(background.width()) + "x" +
                     std::to_string(background.height()) + " but the camera is " + std::to_string(sensor_.width) + "x" +
                     std::to_string(sensor_.height));
  RgbImage image = background;
  const std::vector<OverlayMark> m = marks(camera_from_object);
  // Lines one pixel wide per 320 image columns, so they stay visible in large images.
  const int thickness = std::max(1, sensor_.width / 320);
  for (int v = 0; v < sensor_.height; ++v)
    for (int u = 0; u < sensor_.width; ++u) {
      const OverlayMark mark = m[static_cast<size_t>(v) * static_cast<size_t>(sensor_.width) + static_cast<size_t>(u)];
      if (mark == OverlayMark::Inside) image.blend(u, v, kInside, 0.3);
      if (mark == OverlayMark::Outline) image.fill_rect(u, v, u + thickness, v + thickness, kOutline);
      if (mark == OverlayMark::DepthEdge) image.fill_rect(u, v, u + thickness, v + thickness, kDepthEdge);
    }
  const int scale = std::max(1, sensor_.width / 320), pad = 2 * scale, line_height = text_height(scale) + 2 * scale;
  int box_width = 0;
  for (const auto& line : text) box_width = std::max(box_width, text_width(line, scale));
  if (!text.empty())
    image.fill_rect(0, 0, box_width + 2 * pad, static_cast<int>(text.size()) * line_height + 2 * pad - 2 * scale,
                    {0, 0, 0}, 0.6);
  for (size_t i = 0; i < text.size(); ++i)
    draw_text(image, pad, pad + static_cast<int>(i) * line_height, text[i], kText, scale);
  return image;
}

}  // namespace depthtrack::viz
