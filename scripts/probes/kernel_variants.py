#!/usr/bin/env python3
"""Write variants of render_weigh's kernel text, each a folder for DEPTHTRACK_KERNEL_DIR (the files it
changes; the rest stay the embedded ones), timed against the embedded text by scripts/gpu/tile-variants.sh.
Ablations leave one stage out, for timing only (their results are wrong by design): where a frame's weigh
spends its time, measured as differences, on a GPU with no hardware counters. Candidates are changes
that keep the results, tried before they are built into cl/.

  no_window: visits only the pose's box (the state window's copies outside it are left out; a state
             read that is not a probability is taken as fresh)
  no_draw:   draws no triangle (the box is still found; every pixel is then only carried over)
  no_visits: visits no pixel (the drawing stays; the group's sum is 0)
  no_listed_draws: lists the triangles that draw but draws none of them (the listing's own cost)
  no_culling: draws the triangles facing away too, where the mesh bounds a solid (what culling saves;
             the depths stay the same)
  restrict:  (candidate) render_weigh's buffers declared restrict, so the compiler may move one pixel's
             loads above the last pixel's stores

usage: kernel_variants.py OUTDIR   (run from the repository root)
"""
import pathlib
import sys

VARIANTS = {
    "no_window": [("dt_weigh.h", "return dt_box_union(box, dt_box_make(win.u0, win.v0, win.width, win.height));",
                   "return box;"),
                  # the rows' pixels outside every box now hold whatever was there: read as fresh
                  ("dt_weigh.h", "p = dt_propagate_occlusion(m, kept, now - frame_times[seen]);",
                   "p = dt_propagate_occlusion(m, kept, now - frame_times[seen]);\n  if (!(p >= 0.0f && p <= 1.0f)) p = initial;")],
    "no_draw": [("render_weigh.cl", "          if (rows > 0) {", "          if (0) {"),
                ("render_weigh.cl", "if (!projected) /* each triangle", "if (0) /* each triangle")],
    "no_visits": [("render_weigh.cl", "for (; b < until; b += DT_GROUP_SIZE,", "for (; b < 0u; b += DT_GROUP_SIZE,")],
    "no_listed_draws": [("render_weigh.cl", "for (uint r = lid; r < rows; r += DT_GROUP_SIZE)",
                         "for (uint r = lid; r < 0u; r += DT_GROUP_SIZE)")],
    "no_culling": [("rasterize.cl", "return area != 0.0f && isfinite(area) && !(cam.cull_back_faces && area > 0.0f);",
                    "return area != 0.0f && isfinite(area);")],
}
RESTRICTED = ["__global const float* vertices", "__global const uint* triangles", "__global const float* planes",
              "__global const float* observed", "__global const uint* parents", "__global const float* occlusion_from",
              "__global const dt_u16* time_from", "__global float* occlusion_to", "__global dt_u16* time_to",
              "__global float* log_likelihood", "__global float* log_weight"]
VARIANTS["restrict"] = [("render_weigh.cl", d + ",", d.replace("* ", "* restrict ") + ",") for d in RESTRICTED]


def main():
    out = pathlib.Path(sys.argv[1])
    for name, edits in VARIANTS.items():
        folder = out / name
        folder.mkdir(parents=True, exist_ok=True)
        texts = {}
        for file, old, new in edits:
            text = texts.get(file) or pathlib.Path("cl", file).read_text()
            if text.count(old) != 1:
                sys.exit(f"{name}: '{old}' is not in cl/{file} exactly once")
            texts[file] = text.replace(old, new)
        for file, text in texts.items():
            (folder / file).write_text(text)
        print(name, sorted(texts))


main()
