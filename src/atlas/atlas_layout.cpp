#include "atlas/atlas_layout.hpp"

#include <algorithm>
#include <depthtrack/error.hpp>
#include <string>

namespace depthtrack::render {

AtlasLayout AtlasLayout::make(int tiles, int tile_width, int tile_height, int max_size) {
  if (tile_width > max_size || tile_height > max_size)
    throw InputError("a " + std::to_string(tile_width) + "x" + std::to_string(tile_height) +
                     " tile exceeds the GL render-target limit of " + std::to_string(max_size));
  AtlasLayout layout;
  layout.tile_width = tile_width;
  layout.tile_height = tile_height;
  layout.tiles_per_row = std::max(1, std::min(tiles, max_size / tile_width));
  layout.tiles_per_page = layout.tiles_per_row * (max_size / tile_height);
  for (int first = 0; first < tiles; first += layout.tiles_per_page) {
    const int count = std::min(layout.tiles_per_page, tiles - first);
    const int rows = (count + layout.tiles_per_row - 1) / layout.tiles_per_row;
    layout.pages.push_back({first, count, layout.tiles_per_row * tile_width, rows * tile_height});
  }
  return layout;
}

size_t AtlasLayout::tiles() const {
  size_t n = 0;
  for (const AtlasPageLayout& page : pages) n += static_cast<size_t>(page.tile_count);
  return n;
}

AtlasLayout AtlasLayout::particle_major(int tiles, int tile_width, int tile_height) {
  AtlasLayout layout;
  layout.tile_width = tile_width;
  layout.tile_height = tile_height;
  layout.tiles_per_row = 1;
  layout.tiles_per_page = tiles;
  layout.pages.push_back({0, tiles, tile_width, tiles * tile_height});
  return layout;
}

size_t AtlasLayout::page_offset(size_t p) const {
  return p * static_cast<size_t>(tiles_per_page) * static_cast<size_t>(tile_width) * static_cast<size_t>(tile_height);
}

dt_atlas_layout AtlasLayout::kernel_args() const {
  return dt_atlas_layout{static_cast<dt_u32>(tile_width), static_cast<dt_u32>(tile_height),
                         static_cast<dt_u32>(tiles_per_row), static_cast<dt_u32>(tiles_per_page)};
}

std::vector<float> AtlasLayout::tiles_in_order(const std::vector<float>& buffer, size_t tiles) const {
  const dt_atlas_layout a = kernel_args();
  const size_t pixels = static_cast<size_t>(tile_width) * static_cast<size_t>(tile_height);
  std::vector<float> out(tiles * pixels);
  for (size_t i = 0; i < tiles; ++i) {
    const dt_u64 start = dt_atlas_tile_start(a, static_cast<dt_u32>(i));
    for (size_t k = 0; k < pixels; ++k) out[i * pixels + k] = buffer[dt_atlas_pixel(a, start, static_cast<dt_u32>(k))];
  }
  return out;
}

size_t AtlasLayout::floats() const {
  if (pages.empty()) return 0;
  const AtlasPageLayout& last = pages.back();
  return page_offset(pages.size() - 1) + static_cast<size_t>(last.width) * static_cast<size_t>(last.height);
}

}  // namespace depthtrack::render
