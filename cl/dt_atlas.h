/* Where particle i's depth tile lies in the atlas buffer: the GL atlas's own page layout, copied
 * page by page, so no hand-off has to re-order tiles. Pages follow each other, each
 * tiles_per_page tiles of page_width = tiles_per_row * tile_width pixels per row; tile t of a page
 * sits at tile column t % tiles_per_row, tile row t / tiles_per_row; rows are image rows (no flip).
 * One tile per row (tiles_per_row = 1) is the plain particle-major layout. Host: render::AtlasLayout. */
#ifndef DT_ATLAS_H
#define DT_ATLAS_H
#include "dt_prelude.h"

typedef struct {
  dt_u32 tile_width, tile_height, tiles_per_row, tiles_per_page;
} dt_atlas_layout;

/* Index of the tile's first pixel; pixel (u, v) of the tile is at that + v * page_width + u. */
DT_FN dt_u64 dt_atlas_tile_start(dt_atlas_layout a, dt_u32 particle) {
  const dt_u32 page = particle / a.tiles_per_page, t = particle % a.tiles_per_page;
  const dt_u64 page_width = DT_CAST(dt_u64, a.tiles_per_row) * a.tile_width;
  const dt_u64 page_start = DT_CAST(dt_u64, page) * a.tiles_per_page * a.tile_width * a.tile_height;
  return page_start + DT_CAST(dt_u64, t / a.tiles_per_row) * a.tile_height * page_width +
         DT_CAST(dt_u64, t % a.tiles_per_row) * a.tile_width;
}

/* Index of row-major pixel k (= v * tile_width + u) of the tile that starts at `start`. */
DT_FN dt_u64 dt_atlas_pixel(dt_atlas_layout a, dt_u64 start, dt_u32 k) {
  return start + DT_CAST(dt_u64, k / a.tile_width) * a.tiles_per_row * a.tile_width + k % a.tile_width;
}
#endif
