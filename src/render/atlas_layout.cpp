#include "render/atlas_layout.hpp"

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

size_t AtlasLayout::floats() const {
  if (pages.empty()) return 0;
  const AtlasPageLayout& last = pages.back();
  return page_offset(pages.size() - 1) + static_cast<size_t>(last.width) * static_cast<size_t>(last.height);
}

}  // namespace depthtrack::render
