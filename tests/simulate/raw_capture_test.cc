// The lenslet camera model: lattice geometry, micro-image centres in rendered raw images, agreement of the raw
// capture with the decoded ground truth, and determinism.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/simulate/raw_capture.h"

namespace lfsp::simulate {
namespace {

TEST(Lattice, NearestInvertsCentreAndDecodedSizesMatchLfToolbox) {
  for (const auto& name : CameraPresetNames()) {
    const CameraModel camera = CameraPreset(name);
    const LensSetting& setting = camera.white_settings[static_cast<std::size_t>(camera.capture_setting)];
    const LensletLattice lattice = MakeLattice(camera, setting);
    for (int j = 0; j < lattice.rows; j += 7)
      for (int i = 0; i < lattice.columns; i += 5) {
        const PixelPosition c = lattice.Centre(i, j);
        ASSERT_GE(c.x, 0.5 * lattice.spacing - 1e-3);
        ASSERT_LE(c.x, camera.sensor_width - 1 - 0.5 * lattice.spacing + 1e-3);
        int ii = -1, jj = -1;
        lattice.Nearest(c.x + 0.3, c.y - 0.4, ii, jj);
        ASSERT_EQ(ii, i);
        ASSERT_EQ(jj, j);
      }
    // Hex neighbours are one spacing apart.
    const PixelPosition a = lattice.Centre(3, 4), b = lattice.Centre(4, 4), c = lattice.Centre(3, 5);
    EXPECT_NEAR(std::hypot(b.x - a.x, b.y - a.y), lattice.spacing, 1e-3);
    const double diag = std::hypot(c.x - a.x, c.y - a.y);
    EXPECT_NEAR(diag, lattice.spacing * std::hypot(0.5, 0.8660254 * camera.scale_y), 1e-3);
    const DecodedGrid grid = MakeDecodedGrid(camera, lattice);
    std::printf("%s: spacing %.4f px, %d x %d lenses, decoded %d x %d views of %d x %d, step %.4f px\n", name.c_str(),
                lattice.spacing, lattice.columns, lattice.rows, grid.views, grid.views, grid.width, grid.height,
                grid.view_step);
    if (name == "illum") {  // LFToolbox: 15x15 views of about 434 x 625
      EXPECT_EQ(grid.views, 15);
      EXPECT_NEAR(grid.width, 625, 8);
      EXPECT_NEAR(grid.height, 434, 4);
    }
    if (name == "f01") {  // LFToolbox: 9x9 views of about 380 x 380
      EXPECT_EQ(grid.views, 9);
      EXPECT_NEAR(grid.width, 380, 6);
      EXPECT_NEAR(grid.height, 380, 6);
    }
  }
  EXPECT_THROW(CameraPreset("f02"), Error);
}

// Sub-pixel peak of one micro-image: least-squares paraboloid through the pixels (each divided by its Bayer
// channel's response) within `radius` of `centre`, then its stationary point.
bool FitPeak(const RawCapture& raw, const std::vector<double>& gain, int black, PixelPosition centre, double radius,
             double& px, double& py) {
  std::vector<Eigen::Matrix<double, 6, 1>> rows;
  std::vector<double> values;
  const int x0 = static_cast<int>(std::floor(centre.x - radius)), x1 = static_cast<int>(std::ceil(centre.x + radius));
  const int y0 = static_cast<int>(std::floor(centre.y - radius)), y1 = static_cast<int>(std::ceil(centre.y + radius));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      if (x < 0 || y < 0 || x >= raw.width || y >= raw.height) return false;
      const double dx = x - centre.x, dy = y - centre.y;
      if (dx * dx + dy * dy > radius * radius) continue;
      Eigen::Matrix<double, 6, 1> r;
      r << 1, dx, dy, dx * dx, dx * dy, dy * dy;
      rows.push_back(r);
      const auto k = static_cast<std::size_t>(y * raw.width + x);
      values.push_back((raw.pixels[k] - black) * gain[k]);
    }
  Eigen::MatrixXd a(static_cast<long>(rows.size()), 6);
  Eigen::VectorXd b(static_cast<long>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    a.row(static_cast<long>(k)) = rows[k].transpose();
    b(static_cast<long>(k)) = values[k];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  Eigen::Matrix2d h;
  h << 2 * c(3), c(4), c(4), 2 * c(5);
  const Eigen::Vector2d peak = h.ldlt().solve(-Eigen::Vector2d(c(1), c(2)));
  px = centre.x + peak(0);
  py = centre.y + peak(1);
  return true;
}

// The colour (0 r, 1 g, 2 b) of sensor pixel (x, y)'s filter.
int SensorChannel(const CameraModel& camera, int x, int y) {
  const char c = camera.bayer[static_cast<std::size_t>((y & 1) * 2 + (x & 1))];
  return c == 'r' ? 0 : c == 'g' ? 1 : 2;
}

void CheckMicroImageCentres(const CameraModel& camera, const RawCapture& raw, double max_error, double max_mean) {
  std::vector<double> gain(raw.pixels.size());
  for (int y = 0; y < raw.height; ++y)
    for (int x = 0; x < raw.width; ++x) {
      const char c = camera.bayer[static_cast<std::size_t>((y & 1) * 2 + (x & 1))];
      gain[static_cast<std::size_t>(y * raw.width + x)] = c == 'r'   ? 1.0 / camera.response_r
                                                          : c == 'b' ? 1.0 / camera.response_b
                                                                     : 1.0;
    }
  const double radius = 0.75 * camera.DiscRadius(raw.setting);
  double worst = 0, sum = 0;
  int count = 0;
  for (int j = 0; j < raw.lattice.rows; ++j)
    for (int i = 0; i < raw.lattice.columns; ++i) {
      const PixelPosition c = raw.lattice.Centre(i, j);
      double px = 0, py = 0;
      if (!FitPeak(raw, gain, camera.black, c, radius, px, py)) continue;
      const double e = std::hypot(px - c.x, py - c.y);
      worst = std::max(worst, e);
      sum += e;
      ++count;
    }
  std::printf("%s: %d micro-images, peak-to-model-centre error mean %.4f px, max %.4f px\n", camera.name.c_str(), count,
              sum / count, worst);
  EXPECT_GT(count, raw.lattice.rows * raw.lattice.columns * 9 / 10);
  EXPECT_LT(worst, max_error);
  EXPECT_LT(sum / count, max_mean);
}

TEST(RawCapture, BrightestPointOfEachMicroImageIsTheModelCentre) {
  const CameraModel camera = CameraPreset("mini-illum");
  // A uniformly white scene rendered through the full ray model, without noise: every micro-image peak within 0.1 px.
  Scene white;
  white.name = "white";
  SceneObject wall;
  wall.texture.colour_a = wall.texture.colour_b = {1.0f, 1.0f, 1.0f};
  white.objects.push_back(wall);
  CaptureOptions options;
  options.noise = false;
  CheckMicroImageCentres(camera, RenderRawCapture(white, camera, options), 0.1, 0.02);
  // The white images as written (with noise), at every lens setting: the same within 0.1 px for each micro-image.
  for (int k = 0; k < static_cast<int>(camera.white_settings.size()); k += 2)
    CheckMicroImageCentres(camera, RenderWhiteImage(camera, k, 5), 0.1, 0.03);
}

TEST(RawCapture, RawAgreesWithDecodedGroundTruth) {
  const CameraModel camera = CameraPreset("mini-illum");
  const Scene scene = BuiltinScene("two-horses");
  CaptureOptions options;
  options.noise = false;
  const RawCapture raw = RenderRawCapture(scene, camera, options);
  const RenderedLightField gt = RenderDecodedGroundTruth(scene, camera, options);
  const auto& shape = gt.light_field.shape();
  ASSERT_EQ(shape.nu, raw.grid.views);
  ASSERT_EQ(shape.width, raw.grid.width);
  const int uc = (shape.nu - 1) / 2;
  const double R = camera.DiscRadius(raw.setting);
  const std::array<double, 3> response{camera.response_r, 1.0, camera.response_b};
  const std::array<double, 9> to_sensor = camera.SceneToSensor();
  double se = 0;
  std::size_t n = 0;
  for (int y = 8; y < raw.height - 8; ++y)
    for (int x = 8; x < raw.width - 8; ++x) {
      int i = 0, j = 0;
      raw.lattice.Nearest(x, y, i, j);
      if (i < 1 || j < 1 || i >= raw.lattice.columns - 1 || j >= raw.lattice.rows - 1) continue;
      double along = 0, across = 0;
      raw.lattice.LocalOffset(x, y, i, j, along, across);
      const double s = along / raw.grid.view_step, t = across / raw.grid.view_step;
      const double m = Modulation(camera, raw.lattice, R, x, y, i, j);
      if (m < 0.3 || std::abs(s - std::round(s)) > 0.25 || std::abs(t - std::round(t)) > 0.25) continue;
      const int u = uc + static_cast<int>(std::lround(s)), v = uc + static_cast<int>(std::lround(t));
      const double xd = (i + 0.5 * raw.lattice.Shift(j)) / 0.8660254037844386;
      const int x0 = static_cast<int>(std::floor(xd));
      if (x0 + 1 >= shape.width) continue;
      const int channel = SensorChannel(camera, x, y);
      const double f = xd - x0;
      // The pixel's filter sees the scene through the inverse of the metadata's colour matrix.
      double expected = 0.0;
      for (int k = 0; k < 3; ++k)
        expected += to_sensor[3 * static_cast<std::size_t>(channel) + static_cast<std::size_t>(k)] *
                    ((1 - f) * gt.light_field.at({u, v}, j, x0, k) + f * gt.light_field.at({u, v}, j, x0 + 1, k));
      const double measured = (raw.pixels[static_cast<std::size_t>(y * raw.width + x)] - camera.black) /
                              double(camera.white - camera.black) /
                              (options.exposure * response[static_cast<std::size_t>(channel)] * m);
      se += (measured - expected) * (measured - expected);
      ++n;
    }
  const double psnr = 10 * std::log10(1.0 / (se / n));
  std::printf("raw vs decoded ground truth: %zu samples, PSNR %.2f dB\n", n, psnr);
  EXPECT_GT(n, 50000u);
  EXPECT_GT(psnr, 35.0);  // residual: quantisation, sub-view angular offsets, spatial interpolation
}

// Black everywhere, white from column `edge_px` of the decoded grid rightwards, all on the focal plane (d = 0) so
// that every view sees the edge at the same place.
Scene VerticalEdgeScene(double edge_px, int width) {
  Scene scene;
  scene.name = "edge";
  SceneObject background;
  background.disparity = -0.5f;
  background.texture.colour_a = background.texture.colour_b = {0.0f, 0.0f, 0.0f};
  scene.objects.push_back(background);
  SceneObject white;
  white.label = 1;
  white.shape.kind = Shape::Kind::kRect;
  const auto x0 = static_cast<float>((edge_px + 0.5) / width);  // pixel X = normalised x * W - 0.5
  white.shape.points = {{x0, -0.1f}, {1.1f, 1.1f}};
  white.texture.colour_a = white.texture.colour_b = {1.0f, 1.0f, 1.0f};
  scene.objects.push_back(white);
  return scene;
}

// Where the edge is, read from the sensor pixel nearest each lens centre: in each row of lenses, the lens pitch
// times the summed dark fraction of the lenses, counted from the left edge of the first lens's cell; averaged over
// rows of both parities (their half-lens shift cancels the hexagonal cells' ripple).
double EdgeFromLensCentres(const CameraModel& camera, const RawCapture& raw) {
  const double pitch = 1.0 / 0.8660254037844386;  // decoded pixels between lenses along a row
  const double R = camera.DiscRadius(raw.setting);
  const std::array<double, 3> response{camera.response_r, 1.0, camera.response_b};
  const std::array<double, 9> to_sensor = camera.SceneToSensor();
  double sum = 0;
  int rows = 0;
  for (int j = 2; j + 2 < raw.lattice.rows; ++j) {
    double dark = 0, first_x = 0;
    bool started = false, complete = true;
    for (int i = 0; i < raw.lattice.columns; ++i) {
      const double xd = (i + 0.5 * raw.lattice.Shift(j)) * pitch;
      if (xd < 8 || xd > raw.grid.width - 8) continue;
      const PixelPosition c = raw.lattice.Centre(i, j);
      const int x = static_cast<int>(std::lround(c.x)), y = static_cast<int>(std::lround(c.y));
      if (x < 0 || y < 0 || x >= raw.width || y >= raw.height) {
        complete = false;
        break;
      }
      const int channel = SensorChannel(camera, x, y);
      const double white_signal = to_sensor[3 * static_cast<std::size_t>(channel)] +
                                  to_sensor[3 * static_cast<std::size_t>(channel) + 1] +
                                  to_sensor[3 * static_cast<std::size_t>(channel) + 2];
      const double m = Modulation(camera, raw.lattice, R, x, y, i, j);
      const double covered = (raw.pixels[static_cast<std::size_t>(y * raw.width + x)] - camera.black) /
                             double(camera.white - camera.black) /
                             (raw.exposure * response[static_cast<std::size_t>(channel)] * m * white_signal);
      if (!started) first_x = xd - 0.5 * pitch;
      started = true;
      dark += 1.0 - covered;
    }
    if (!started || !complete) continue;
    sum += first_x + pitch * dark;
    ++rows;
  }
  EXPECT_GT(rows, 20);
  return sum / rows;
}

// A sensor pixel receives its direction's light through the whole micro-lens, so each lens reads the scene averaged
// over its aperture: moving an edge by a quarter of a decoded pixel moves the edge read from the lens centres by as
// much. Rays through the lens centres alone (lens_samples 1) read it in steps of whole lenses, which left simulated
// checkerboard corners 0.27 px off in the decoded views.
TEST(RawCapture, EachLensAveragesTheSceneOverItsAperture) {
  const CameraModel camera = CameraPreset("mini-f01");
  CaptureOptions options;
  options.noise = false;
  const int width = RenderRawCapture(VerticalEdgeScene(40, 100), camera, options).grid.width;
  const auto edge_read = [&](double edge_px, int lens_samples) {
    CaptureOptions o = options;
    o.lens_samples = lens_samples;
    return EdgeFromLensCentres(camera, RenderRawCapture(VerticalEdgeScene(edge_px, width), camera, o));
  };
  // Worst error of the edge read over five positions 0.23 px apart, with `lens_samples` rays per axis.
  const auto worst_error = [&](int lens_samples) {
    double worst = 0;
    for (int step = 0; step < 5; ++step) {
      const double edge = 0.45 * width + 0.23 * step;
      worst = std::max(worst, std::abs(edge_read(edge, lens_samples) - edge));
    }
    return worst;
  };
  const double calibration = worst_error(kCalibrationLensSamples), two = worst_error(2), centre_only = worst_error(1);
  std::printf(
      "worst edge error: %.3f px with %d x %d rays (checkerboard sets), %.3f px with 2 x 2, %.3f px through "
      "lens centres only\n",
      calibration, kCalibrationLensSamples, kCalibrationLensSamples, two, centre_only);
  EXPECT_LT(calibration, 0.04);  // measured 0.028 px
  EXPECT_LT(two, 0.16);          // measured 0.124 px (steps of a quarter of a lens)
  EXPECT_GT(centre_only, 0.1);   // the failure this guards against is visible at these positions
}

TEST(RawCapture, DeterministicForASeedAndDifferentForAnother) {
  const CameraModel camera = CameraPreset("mini-illum");
  const Scene scene = BuiltinScene("planes");
  CaptureOptions options;
  options.seed = 42;
  options.hot_pixels = 5;
  const RawCapture a = RenderRawCapture(scene, camera, options);
  const RawCapture b = RenderRawCapture(scene, camera, options);
  EXPECT_EQ(a.pixels, b.pixels);
  ASSERT_EQ(a.hot_pixels.size(), 5u);
  for (const auto& p : a.hot_pixels) EXPECT_EQ(a.pixels[static_cast<std::size_t>(p[1] * a.width + p[0])], camera.white);
  options.seed = 43;
  const RawCapture c = RenderRawCapture(scene, camera, options);
  EXPECT_NE(a.pixels, c.pixels);
  // Noise has the modelled size: in a black scene every pixel is black level + read noise.
  Scene black;
  black.objects.push_back(SceneObject{});
  black.objects[0].texture.colour_a = {0.0f, 0.0f, 0.0f};
  const RawCapture d = RenderRawCapture(black, camera, options);
  double sum = 0, sum2 = 0;
  for (const auto p : d.pixels) {
    sum += p;
    sum2 += static_cast<double>(p) * p;
  }
  const double n = static_cast<double>(d.pixels.size()) - 5;  // minus the hot pixels
  const double mean = (sum - 5.0 * camera.white) / n;
  const double sd = std::sqrt((sum2 - 5.0 * camera.white * camera.white) / n - mean * mean);
  EXPECT_NEAR(mean, camera.black, 0.05);
  EXPECT_NEAR(sd, std::sqrt(camera.read_noise * camera.read_noise + 1.0 / 12.0), 0.05);  // + rounding to integers
}

}  // namespace
}  // namespace lfsp::simulate
