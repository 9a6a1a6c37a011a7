#pragma once
// Where each pose's tile lies: tile i of a page at column i % tiles_per_row, row i / tiles_per_row;
// a page holds at most tiles_per_page tiles, so that no page exceeds the GL's render-target limit.
// The compute kernels read the pages in this same layout (cl/dt_atlas.h).
#include <cstddef>
#include <vector>

#include "dt_atlas.h"

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
  // One tile per row in a single page: tile i is the i-th block of width x height floats.
  static AtlasLayout particle_major(int tiles, int tile_width, int tile_height);
  // Floats of a buffer holding every page back to back (page p starts at p * tiles_per_page tiles).
  size_t floats() const;
  // Tiles over all pages.
  size_t tiles() const;
  // Index of page p's first float in that buffer.
  size_t page_offset(size_t p) const;
  // This layout as the kernels take it (cl/dt_atlas.h).
  dt_atlas_layout kernel_args() const;
  // The first `tiles` tiles of such a buffer, one row-major block each, in tile order.
  std::vector<float> tiles_in_order(const std::vector<float>& buffer, size_t tiles) const;
  bool operator==(const AtlasLayout&) const = default;
};

}  // namespace depthtrack::render
