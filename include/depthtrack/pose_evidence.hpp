#pragma once
/// @file
/// What the depth says about an estimated pose: the shares of its rendered silhouette that the frame
/// explains, contradicts or cannot judge, and whether its outline stands out from what lies behind.
/// The tracker's confidence is a calibrated function of these (docs/confidence.md).

namespace depthtrack {

/// What the depth says about one pose (see the file's notes); every share is in [0, 1].
struct PoseEvidence {
  int pixels = 0;  ///< pixels the pose's silhouette covers at the working resolution
  /// Of the silhouette's pixels with a valid depth y, where the pose renders depth y_hat and sigma(y) is the
  /// observation model's noise: |y - y_hat| within loss.pixel_sigmas sigma (visible), y in front of the
  /// surface (occluded: something hides it), y behind it (contradicted: the camera sees through where the
  /// object would be). The three add up to 1.
  double visible = 0, occluded = 0, contradicted = 0;
  double missing = 0;  ///< of all the silhouette's pixels: no valid depth
  /// Of the outline's outer neighbours not seen in front of the edge: the share where the camera sees
  /// past the object's edge (depth behind it, or none). A pose pressed into a wall has no such outline.
  double separated = 0;
  double outline_nearer = 0;  ///< of all the outline's outer neighbours: seen in front of the edge
  /// Root mean square of (y - y_hat) / sigma(y) over the visible pixels: below 1 where the surface lies
  /// where the pose puts it, larger where some other surface merely falls within the band.
  double visible_rms = 0;
  // The same for the best plane through the visible pixels' measured depths (weighted least squares in
  // pixel coordinates): near visible_rms where a flat surface (a wall, a table) explains them as well as
  // the object does, larger where the seen surface has the object's relief (a bowl's curve, a box's two
  // faces). visible_rms when fewer than 16 pixels are visible.
  double plane_rms = 0;
};

}  // namespace depthtrack
