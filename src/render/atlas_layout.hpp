#pragma once
// Where each pose's tile lies: tile i of a page at column i % tiles_per_row, row i / tiles_per_row;
// a page holds at most tiles_per_page tiles, so that no page exceeds the GL's render-target limit.
#include <vector>

namespace depthtrack::render {

struct AtlasPageLayout {
  int first_tile = 0, tile_count = 0;
  int width = 0, height = 0;  // pixels
  bool operator==(const AtlasPageLayout&) const = default;
};

struct AtlasLayout {
  int tile_width = 0, tile_height = 0;
  int tiles_per_row = 0, tiles_per_page = 0;
  std::vector<AtlasPageLayout> pages;

  // InputError when a single tile exceeds max_size.
  static AtlasLayout make(int tiles, int tile_width, int tile_height, int max_size);
  bool operator==(const AtlasLayout&) const = default;
};

}  // namespace depthtrack::render
