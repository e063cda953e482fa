#pragma once

// The index and disparity conventions of docs/DESIGN.md, as named helpers, so no stage re-derives them.
//   u: angular column (horizontal view index), v: angular row; x: pixel column, y: pixel row.
//   Views are numbered row-major: cam = v * nu + u.  Centre view (uc, vc) = ((nu-1)/2, (nv-1)/2).
//   A centre-view pixel (x, y) with disparity d appears in view (u, v) at (x - (u-uc)*d, y - (v-vc)*d).
//   Positive d is in front of the focal plane (HCI benchmark convention).

namespace lfsp {

struct ViewIndex {
  int u = 0;  // angular column
  int v = 0;  // angular row
  friend bool operator==(const ViewIndex&, const ViewIndex&) = default;
};

struct PixelPosition {
  float x = 0.0f;  // column
  float y = 0.0f;  // row
};

// Row-major camera number of view (u, v) in an nu-wide grid (HCI: input_Cam%03d).
constexpr int CameraNumber(ViewIndex view, int nu) { return view.v * nu + view.u; }

constexpr ViewIndex ViewFromCameraNumber(int cam, int nu) { return {cam % nu, cam / nu}; }

constexpr ViewIndex CentreView(int nu, int nv) { return {(nu - 1) / 2, (nv - 1) / 2}; }

// Where the centre-view pixel (x, y) with disparity d lands in view (u, v).
constexpr PixelPosition ProjectFromCentre(PixelPosition centre_pixel, float disparity, ViewIndex view,
                                          ViewIndex centre) {
  return {centre_pixel.x - static_cast<float>(view.u - centre.u) * disparity,
          centre_pixel.y - static_cast<float>(view.v - centre.v) * disparity};
}

}  // namespace lfsp
