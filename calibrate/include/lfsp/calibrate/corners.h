#pragma once

// Checkerboard corners in every sub-aperture view of a decoded capture.
//
// The board is found once, with OpenCV's findChessboardCornersSB, in the brightest view nearest the centre of the
// view grid. Its corners are put in a canonical order (below) and then followed from view to view, ring by ring
// away from that view: each view's corners are predicted from its already-found neighbours (the board only shifts
// by its disparity between views) and refined with cornerSubPix, then moved to the saddle point of the blurred view
// (saddle_refinement.h; cornerSubPix alone is pulled towards the pixel grid). So every view of a capture has the same
// corner order by construction, and the slow full-image search runs once per capture instead of once per view.
//
// Canonical order: corner (a, b) is stored at b * corners_x + a, with a increasing along the board direction that
// points most to the right in the image and b increasing downwards (the ordering is never mirrored). A board with
// an even number of squares per side looks the same after a half turn, so any consistent order is valid; this one
// makes the board frame (x along a, y along b, z into the board) face the camera.

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "lfsp/core/light_field.h"

namespace lfsp::calibrate {

struct CornerDetectionOptions {
  int corners_x = 19;  // inner corners per board row (0 with corners_y 0: a partial board, below)
  int corners_y = 19;  // inner corners per board column
  // corners_x = corners_y = 0: the board may overflow the views (close-up captures). The reference view's whole
  // visible grid is taken (OpenCV's CALIB_CB_LARGER), less the rows and columns within one square of the view's
  // edge (parallax moves them out of other views); CaptureCorners records the size used. Corner indices then count
  // from the first visible corner, so each capture has its own board origin (its pose absorbs it).
  double min_view_weight = 0.2;  // views whose mean weight is below this are skipped as dark (LFToolbox: 0.2)
  // Views within this many view steps of the lenslet's edge are skipped: of a dark view or of the edge of the view
  // grid. Their pixels sit at the rim of the micro-lens image, where the main lens's aperture cuts off part of what
  // the pixel would see, so they look through a point nearer the aperture's centre than the view's index says, which
  // the linear ray model cannot follow. On full-size F01 decodes of a checkerboard (`lfsp simulate --calibration 8`)
  // their corners sat 0.08-0.13 px towards the central view's, against 0.02-0.04 px rms and a mean below 0.01 px in
  // the views inside. -1 = automatic: 1 (LFToolbox's LensletBorderSize) on light fields decoded from a lenslet
  // capture, 0 on others (rendered light fields and views folders, whose edge is not known to be a lenslet's).
  int view_border = -1;
  double max_grid_residual = 0.5;  // px: a view whose corners do not follow a homography of the reference view's
                                   // corners to this RMS is rejected as a failed detection
};

struct ViewCorners {
  ViewIndex view;
  std::vector<cv::Point2d> corners;  // canonical order, pixels (pixel centres at integers)
};

struct CaptureCorners {
  std::string name;  // the capture's file name, for messages
  LightFieldShape shape;
  int corners_x = 0;
  int corners_y = 0;
  bool partial_board = false;         // found in partial-board mode: the grid size is this capture's own
  ViewIndex reference;                // where the board was searched for
  std::vector<ViewCorners> views;     // every view with a complete detection, same corner order
  std::vector<ViewIndex> dark_views;  // skipped for low weight
  std::vector<ViewIndex> edge_views;  // bright enough, but skipped within view_border of the lenslet's edge
  std::vector<ViewIndex> failed_views;
  // Camera facts from the light field's metadata (camera.model / serial / zoom_step / focus_step), if recorded.
  std::string camera_model;
  std::string serial;
  std::optional<int> zoom_step;
  std::optional<int> focus_step;
};

// Finds the board in every usable view. Throws lfsp::Error naming the capture when the board (of the expected
// number of corners) is not found in any of the central views.
CaptureCorners DetectCaptureCorners(const LightField& light_field, const std::string& name,
                                    const CornerDetectionOptions& options = {});

// Mean weight of each view (row-major cam order): the recorded weights, or, without them, the view's mean
// brightness relative to the brightest view.
std::vector<double> ViewWeights(const LightField& light_field);

// The view as one grey float image (mean of the channels).
cv::Mat GreyView(const LightField& light_field, ViewIndex view);

// Puts a full grid of corners (row-major, corners_x per row) in the canonical order described above. Returns
// false if no unmirrored order exists (the detection was mirrored or degenerate).
bool CanonicalCornerOrder(std::vector<cv::Point2d>& corners, int corners_x, int corners_y);

}  // namespace lfsp::calibrate
