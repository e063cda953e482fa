#include "lfsp/simulate/simulate.h"

#include "lfsp/core/error.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/decode/lfp_container.h"
#include "lfsp/simulate/calibration_set.h"
#include "lfsp/simulate/evaluation_masks.h"
#include "lfsp/simulate/lenslet_camera.h"
#include "lfsp/simulate/lytro_writer.h"
#include "lfsp/simulate/render.h"

namespace lfsp::simulate {
namespace {

void WriteText(const std::string& text, const std::filesystem::path& path) {
  decode::WriteFileBytesAtomic(
      std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), path);
}

// The ideal renderer's settings for an --ideal-only run, the same for the scene and for every calibration pose.
RenderOptions IdealRenderOptions(const SimulateOptions& options) {
  RenderOptions render;
  render.nu = render.nv = options.views;
  render.width = options.width;
  render.height = options.height;
  render.supersampling = options.supersampling;
  render.per_view_disparity = false;
  return render;
}

// whites/MOD_####.RAW + .TXT for every lens setting of the camera; returns their description.
nlohmann::json WriteWhiteImages(const CameraModel& camera, std::uint64_t seed, const std::filesystem::path& out_dir,
                                SimulateResult& result) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir / "whites", ec);
  if (ec) ThrowFileError((out_dir / "whites").string(), "cannot create folder: " + ec.message());
  nlohmann::json whites = nlohmann::json::array();
  for (int k = 0; k < static_cast<int>(camera.white_settings.size()); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "MOD_%04d.RAW", k);
    const RawCapture white = RenderWhiteImage(camera, k, seed);
    WriteWhiteImage(camera, white, out_dir / "whites" / name);
    result.files.push_back(std::filesystem::path("whites") / name);
    result.files.push_back((std::filesystem::path("whites") / name).replace_extension(".TXT"));
    whites.push_back({{"file", std::string("whites/") + name},
                      {"zoomStep", white.setting.zoom_step},
                      {"focusStep", white.setting.focus_step},
                      {"spacing_px", white.lattice.spacing},
                      {"origin_px", {white.lattice.origin_x, white.lattice.origin_y}},
                      {"matches_capture", k == camera.capture_setting}});
  }
  return whites;
}

// The checkerboard set: one capture (or ideal light field) per pose, each with its calibration ground truth.
void WriteCalibrationSet(const SimulateOptions& options, const std::filesystem::path& out_dir, SimulateResult& result) {
  const auto boards = CalibrationBoards(options.calibration_poses);
  const BundleWriteOptions bundle_options{options.ground_truth_storage, options.compression_level};
  nlohmann::json poses = nlohmann::json::array();
  for (std::size_t k = 0; k < boards.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "pose_%02zu", k);
    const std::filesystem::path folder = std::filesystem::path("calibration") / name;
    std::error_code ec;
    std::filesystem::create_directories(out_dir / folder, ec);
    if (ec) ThrowFileError((out_dir / folder).string(), "cannot create folder: " + ec.message());
    const Scene scene = CalibrationScene(boards[k], CalibrationRig());
    nlohmann::json truth;
    if (options.ideal_only) {
      WriteBundle(ToBundle(RenderLightField(scene, IdealRenderOptions(options)), scene), out_dir / folder / "ideal.h5",
                  bundle_options);
      result.files.push_back(folder / "ideal.h5");
      truth = CalibrationGroundTruth(scene, options.width, options.height);
    } else {
      const CameraModel camera = CameraPreset(options.camera);
      CaptureOptions capture = options.capture;
      capture.seed = options.seed + k;
      if (capture.lens_samples == 0) capture.lens_samples = kCalibrationLensSamples;
      const RawCapture raw = RenderRawCapture(scene, camera, capture);
      const std::string capture_name = CaptureFileName(camera);
      decode::WriteLfpContainer(BuildCaptureContainer(camera, raw), out_dir / folder / capture_name);
      result.files.push_back(folder / capture_name);
      // Intrinsics in the decoded grid's pixel frame (what a decoder outputs), plus the sensor geometry.
      truth = CalibrationGroundTruth(scene, raw.grid.width, raw.grid.height);
      truth["lenslet_geometry"] = LensletGeometryJson(camera, raw);
    }
    WriteText(truth.dump(2), out_dir / folder / "ground_truth.json");
    result.files.push_back(folder / "ground_truth.json");
    poses.push_back(folder.generic_string());
  }
  result.summary["calibration_poses"] = poses;
}

// Every option checked before the output folder is made: `--disparity-scale inf` was refused only after the capture,
// the white images and the geometry were written, `--size 100000x100000` after an empty folder was made.
void CheckSimulateOptions(const SimulateOptions& options) {
  if (options.compression_level < 0 || options.compression_level > 9)
    throw Error("simulate: compression level must be 0..9");
  if (options.calibration_poses < 0) throw Error("simulate: calibration poses must be >= 0");
  if (options.mosaic_jpeg_quality < 0 || options.mosaic_jpeg_quality > 100)
    throw Error("simulate: mosaic JPEG quality must be 0 (none) .. 100");
  if (options.ideal_only) {
    CheckRenderOptions(IdealRenderOptions(options));
  } else {
    (void)CameraPreset(options.camera);  // an unknown name throws
    CheckCaptureOptions(options.capture);
  }
}

// What a failed run wrote is removed: the whole folder if the run made it, else the files it wrote and the
// sub-folders they emptied.
class PartialRun {
 public:
  PartialRun(const std::filesystem::path& out_dir, const SimulateResult& result) : out_dir_(out_dir), result_(result) {
    std::error_code ec;
    made_folder_ = !std::filesystem::exists(out_dir, ec);
  }
  ~PartialRun() {
    if (finished_) return;
    std::error_code ec;
    if (made_folder_) {
      std::filesystem::remove_all(out_dir_, ec);
      return;
    }
    for (const std::filesystem::path& file : result_.files) {
      std::filesystem::remove(out_dir_ / file, ec);
      for (std::filesystem::path folder = file.parent_path(); !folder.empty(); folder = folder.parent_path())
        std::filesystem::remove(out_dir_ / folder, ec);  // only if empty
    }
  }
  void Finish() { finished_ = true; }

 private:
  std::filesystem::path out_dir_;
  const SimulateResult& result_;
  bool made_folder_ = false;
  bool finished_ = false;
};

}  // namespace

SimulateResult Simulate(const SimulateOptions& options, const std::filesystem::path& out_dir) {
  const Stopwatch total;
  CheckSimulateOptions(options);
  const Scene scene = SceneFromSpec(options.scene);
  SimulateResult result;
  PartialRun partial_run(out_dir, result);
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) ThrowFileError(out_dir.string(), "cannot create output folder: " + ec.message());
  nlohmann::json& summary = result.summary;
  summary["command"] = "simulate";
  summary["scene"] = scene.name;
  summary["seed"] = options.seed;
  const auto range = scene.DisparityRange();
  summary["scene_disparity_range"] = {range[0], range[1]};
  const BundleWriteOptions bundle_options{options.ground_truth_storage, options.compression_level};

  if (options.calibration_poses > 0) {
    // The checkerboard set (the scene is not rendered), then white images as for any capture.
    WriteCalibrationSet(options, out_dir, result);
    if (!options.ideal_only && options.white_images)
      summary["white_images"] = WriteWhiteImages(CameraPreset(options.camera), options.seed, out_dir, result);
  } else if (options.ideal_only) {
    const Stopwatch stopwatch;
    const RenderedLightField rendered = RenderLightField(scene, IdealRenderOptions(options));
    summary["timings_s"]["render_ideal"] = stopwatch.Seconds();
    WriteBundle(ToBundle(rendered, scene), out_dir / "ideal.h5", bundle_options);
    result.files.push_back("ideal.h5");
    // The benchmark's evaluation regions beside the ground truth, where `lfsp evaluate depth` looks for them.
    WriteEvaluationMasks(EvaluationMasksOf(rendered, scene), out_dir);
    for (const char* name : kEvaluationMaskFiles) result.files.push_back(name);
    summary["ideal"] = {{"views", options.views}, {"width", options.width}, {"height", options.height}};
  } else {
    const CameraModel camera = CameraPreset(options.camera);
    CaptureOptions capture = options.capture;
    capture.seed = options.seed;
    summary["camera"] = camera.name;
    Stopwatch step;
    const RawCapture raw = RenderRawCapture(scene, camera, capture);
    summary["timings_s"]["render_raw"] = step.Lap();
    const std::string capture_name = CaptureFileName(camera);
    decode::WriteLfpContainer(BuildCaptureContainer(camera, raw), out_dir / capture_name);
    result.files.push_back(capture_name);
    if (options.mosaic_jpeg_quality > 0) {
      WriteMosaicJpeg(camera, raw, out_dir / kMosaicJpegName, options.mosaic_jpeg_quality);
      result.files.push_back(kMosaicJpegName);
      result.files.push_back(std::filesystem::path(kMosaicJpegName).replace_extension(".png"));
    }

    if (options.white_images) {
      step.Lap();
      summary["white_images"] = WriteWhiteImages(camera, options.seed, out_dir, result);
      summary["timings_s"]["render_whites"] = step.Lap();
    }

    std::filesystem::create_directories(out_dir / "ground_truth", ec);
    if (ec) ThrowFileError((out_dir / "ground_truth").string(), "cannot create folder: " + ec.message());
    nlohmann::json geometry = LensletGeometryJson(camera, raw);
    if (summary.contains("white_images")) geometry["white_images"] = summary["white_images"];
    WriteText(geometry.dump(2), out_dir / "ground_truth" / "lenslet_geometry.json");
    result.files.push_back("ground_truth/lenslet_geometry.json");
    step.Lap();
    const RenderedLightField gt = RenderDecodedGroundTruth(scene, camera, capture, options.ground_truth_supersampling);
    summary["timings_s"]["render_ground_truth"] = step.Lap();
    WriteBundle(ToBundle(gt, scene), out_dir / "ground_truth" / "decoded.h5", bundle_options);
    result.files.push_back("ground_truth/decoded.h5");
    summary["capture"] = {
        {"file", capture_name},
        {"sensor", {raw.width, raw.height}},
        {"lenses", {raw.lattice.columns, raw.lattice.rows}},
        {"decoded", {{"views", raw.grid.views}, {"width", raw.grid.width}, {"height", raw.grid.height}}},
        {"exposure", capture.exposure},
        {"noise", capture.noise},
        {"hot_pixels", capture.hot_pixels}};
  }
  // The scene description last: a folder with scene.json holds everything rendered from it (a killed run leaves
  // no scene.json beside missing files). Calibration sets describe their boards in each ground_truth.json.
  if (options.calibration_poses == 0) {
    WriteText(SceneToJson(scene).dump(2), out_dir / "scene.json");
    result.files.push_back("scene.json");
  }
  nlohmann::json files = nlohmann::json::array();
  for (const auto& f : result.files) files.push_back(f.generic_string());
  summary["files"] = files;
  summary["timings_s"]["total"] = total.Seconds();
  partial_run.Finish();
  return result;
}

}  // namespace lfsp::simulate
