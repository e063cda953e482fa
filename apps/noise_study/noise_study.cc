#include "noise_study.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/progress.h"
#include "lfsp/core/stats.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/core/view_crop.h"
#include "lfsp/core/visualize.h"
#include "lfsp/decode/capture_decoder.h"
#include "lfsp/depth/depth_estimator.h"
#include "lfsp/segment/baselines.h"
#include "lfsp/segment/evaluate.h"
#include "lfsp/segment/lfsp.h"
#include "lfsp/segment/metrics.h"
#include "lfsp/simulate/image_noise.h"
#include "lfsp/simulate/lenslet_camera.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"
#include "lfsp/simulate/simulate.h"
#include "line_plot.h"
#include "stages/summary.h"

namespace lfsp::noise_study {
namespace fs = std::filesystem;

namespace {

// The metrics plotted against noise, as named in segment::ScoreLabels.
const std::vector<std::string> kPlottedMetrics = {"self_similarity",  "elr",
                                                  "boundary_recall",  "undersegmentation_error",
                                                  "labels_per_pixel", "achievable_segmentation_accuracy"};

// A noisy light field with its ground truth.
struct Trial {
  LightField light_field;
  Labels gt_labels;
  DisparityMap gt_disparity;
  std::vector<DisparityMap> gt_view_disparity;
  int size = 16;
};

struct Row {
  std::string noise;
  double level = 0.0;  // sigma, or exposure
  double x = 0.0;      // the plotted noise measure
  std::string method;
  nlohmann::json metrics;
};

DisparityRange RangeOf(const DisparityMap& disparity) {
  DisparityRange range{INFINITY, -INFINITY};
  for (int i = 0; i < disparity.width() * disparity.height(); ++i) {
    const float d = disparity.data()[i];
    if (!std::isfinite(d)) continue;
    range.min = std::min(range.min, d);
    range.max = std::max(range.max, d);
  }
  const float pad = 0.1f * (range.max - range.min) + 0.05f;
  return {range.min - pad, range.max + pad};
}

// Depth from the noisy light field, then LFSP on it, and the per-view baselines, each scored against the truth.
std::vector<std::pair<std::string, nlohmann::json>> SegmentAndScore(const Trial& trial, bool lsc) {
  std::vector<std::pair<std::string, nlohmann::json>> scores;
  // Per-view baselines are followed across views before their self-similarity is measured, as in `lfsp evaluate`.
  auto score = [&](const std::string& method, const Labels& labels, double seconds) {
    const bool per_view = method != "lfsp";
    nlohmann::json metrics =
        per_view
            ? segment::ScorePerViewLabels(labels, &trial.gt_labels, &trial.gt_disparity, &trial.gt_view_disparity, 2)
            : segment::ScoreLabels(labels, &trial.gt_labels, &trial.gt_disparity, &trial.gt_view_disparity, 2);
    metrics.erase("note");
    metrics["seconds"] = seconds;
    scores.emplace_back(method, std::move(metrics));
  };
  // Each method is timed from its start to its labels; the scoring that follows is not part of its time.
  Stopwatch step;
  depth::DepthOptions depth_options;
  depth_options.range = RangeOf(trial.gt_disparity);
  const DisparityMap disparity = depth::EstimateDepth(trial.light_field, depth_options).disparity;
  segment::LfspParams params;
  params.size = trial.size;
  const Labels lfsp_labels = segment::SegmentLightField(trial.light_field, disparity, params).labels;
  score("lfsp", lfsp_labels, step.Seconds());

  segment::BaselineParams baseline;
  baseline.size = trial.size;
  step.Lap();
  const Labels slic = segment::SlicPerView(trial.light_field, baseline);
  score("slic_per_view", slic, step.Seconds());
  if (lsc) {
    step.Lap();
    const Labels lsc_labels = segment::LscPerView(trial.light_field, baseline);
    score("lsc_per_view", lsc_labels, step.Seconds());
  }
  return scores;
}

// Clamps to [0, 1] and sRGB-encodes a scene-linear light field in place, so that every method sees what a decode in
// camera colour would give.
void EncodeForDisplay(LightField& light_field) {
  if (light_field.transfer != Transfer::kLinear) return;
  const LightFieldShape& shape = light_field.shape();
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u) {
      cv::Mat view = light_field.View(ViewIndex{u, v});
      DisplayEncoded(view, Transfer::kLinear).copyTo(view);
    }
  light_field.transfer = Transfer::kSrgb;
}

// Renders the lenslet capture at `exposure`, decodes it, and scales it back to the reference brightness. The white
// images are rendered with the first capture only (they do not depend on the exposure) and found in `whites`.
Trial LowLightTrial(const NoiseStudyOptions& options, double exposure, const fs::path& work, const fs::path& whites) {
  simulate::SimulateOptions simulate_options;
  simulate_options.scene = options.scene;
  simulate_options.camera = options.camera;
  simulate_options.seed = options.seed;
  simulate_options.capture.exposure = exposure;
  simulate_options.white_images = !fs::exists(whites);
  const fs::path folder = work / ("exposure_" + std::to_string(exposure));
  simulate::Simulate(simulate_options, folder);
  if (simulate_options.white_images) fs::rename(folder / "whites", whites);
  fs::path capture;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().stem() == "capture") capture = entry.path();
  decode::CaptureDecodeOptions decode_options;
  decode_options.white_images = whites;
  decode_options.decode.colour = decode::ColourMode::kLinear;
  decode::CaptureDecodeResult decoded = decode::DecodeCaptureFile(capture, decode_options);
  Bundle truth = ReadBundle(folder / "ground_truth" / "decoded.h5");
  if (!truth.labels || !truth.disparity) ThrowFileError(folder.string(), "simulated ground truth lacks labels");
  if (!(truth.light_field.shape() == decoded.light_field.shape()))
    throw Error("decoded capture " + ToString(decoded.light_field.shape()) + " does not match its ground truth " +
                ToString(truth.light_field.shape()));
  fs::remove_all(folder);
  // The outer views are dropped first, so the gain and the encoding touch only the views that are kept.
  Trial trial;
  const int views = decoded.light_field.shape().nu;
  const int keep = options.capture_views > 0 ? std::min(options.capture_views, views) : views;
  trial.light_field = keep == views ? std::move(decoded.light_field) : CentralViews(decoded.light_field, keep);
  trial.gt_labels = keep == views ? std::move(*truth.labels) : CentralViews(*truth.labels, keep);
  // The gain back to the reference brightness is applied to scene-linear values: applied after the sRGB curve it
  // would blow most of a dim capture out to white instead of showing its noise.
  const float gain = static_cast<float>(options.exposures.front() / exposure);
  for (std::size_t i = 0; i < trial.light_field.size(); ++i) trial.light_field.data()[i] *= gain;
  EncodeForDisplay(trial.light_field);
  trial.gt_disparity = std::move(*truth.disparity);
  trial.gt_view_disparity = segment::PropagateDisparity(trial.gt_disparity, trial.light_field.shape());
  trial.size = options.capture_size;
  return trial;
}

// Mean sample value and the share of samples at 1 (clipped): shows that every level has the reference brightness.
nlohmann::ordered_json Brightness(const LightField& light_field) {
  const auto clipped = std::count_if(light_field.data(), light_field.data() + light_field.size(),
                                     [](float value) { return value >= 1.0f; });
  return {{"mean", ComputeStats(light_field.data(), light_field.size()).mean},
          {"clipped_fraction",
           static_cast<double>(clipped) / static_cast<double>(std::max<std::size_t>(1, light_field.size()))}};
}

std::string CsvValue(const nlohmann::json& value) {
  if (value.is_number()) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value.get<double>());
    return text;
  }
  return "";
}

void WriteCsv(const std::vector<Row>& rows, const fs::path& path) {
  std::vector<std::string> columns;
  for (const Row& row : rows)
    for (const auto& [key, value] : row.metrics.items())
      if (value.is_number() && std::find(columns.begin(), columns.end(), key) == columns.end()) columns.push_back(key);
  AtomicOutput output(path);
  {
    std::ofstream file(output.temporary());
    file << "noise,level,noise_measure,method";
    for (const auto& column : columns) file << "," << column;
    file << "\n";
    for (const Row& row : rows) {
      file << row.noise << "," << row.level << "," << row.x << "," << row.method;
      for (const auto& column : columns)
        file << "," << (row.metrics.contains(column) ? CsvValue(row.metrics[column]) : "");
      file << "\n";
    }
    if (!file.flush()) ThrowFileError(path.string(), "write failed");
  }
  output.Commit();
}

std::vector<fs::path> WritePlots(const std::vector<Row>& rows, const std::string& noise, const std::string& x_label,
                                 const fs::path& out) {
  std::vector<double> x;
  std::vector<std::string> methods;
  for (const Row& row : rows) {
    if (row.noise != noise) continue;
    if (std::find(x.begin(), x.end(), row.x) == x.end()) x.push_back(row.x);
    if (std::find(methods.begin(), methods.end(), row.method) == methods.end()) methods.push_back(row.method);
  }
  std::vector<fs::path> written;
  for (const std::string& metric : kPlottedMetrics) {
    std::vector<PlotSeries> series;
    for (const std::string& method : methods) {
      PlotSeries s{method, std::vector<double>(x.size(), NAN)};
      for (const Row& row : rows)
        if (row.noise == noise && row.method == method && row.metrics.contains(metric) &&
            row.metrics[metric].is_number())
          s.y[std::find(x.begin(), x.end(), row.x) - x.begin()] = row.metrics[metric].get<double>();
      series.push_back(s);
    }
    const fs::path path = out / ("plot_" + noise + "_" + metric + ".png");
    WriteImage(LinePlot(metric + " vs " + noise + " noise", x_label, metric, x, series), path);
    written.push_back(path);
  }
  return written;
}

// How much each method's SS and ELR change from the cleanest to the noisiest level: the study's headline.
nlohmann::ordered_json Degradation(const std::vector<Row>& rows) {
  nlohmann::ordered_json out;
  for (const std::string noise : {"image", "lowlight"}) {
    std::map<std::string, std::pair<const Row*, const Row*>> ends;  // method -> (cleanest, noisiest)
    for (const Row& row : rows) {
      if (row.noise != noise) continue;
      auto& [first, last] = ends[row.method];
      if (first == nullptr || row.x < first->x) first = &row;
      if (last == nullptr || row.x > last->x) last = &row;
    }
    for (const auto& [method, pair] : ends) {
      for (const std::string metric : {"self_similarity", "elr"}) {
        const auto& a = pair.first->metrics;
        const auto& b = pair.second->metrics;
        if (a.contains(metric) && b.contains(metric) && a[metric].is_number() && b[metric].is_number())
          out[noise][method][metric + "_change"] = b[metric].get<double>() - a[metric].get<double>();
      }
    }
  }
  return out;
}

simulate::RenderOptions IdealRenderOptions(const NoiseStudyOptions& options) {
  simulate::RenderOptions render;
  render.nu = render.nv = options.views;
  render.width = options.width;
  render.height = options.height;
  return render;
}

// Every option is checked before the first rendering: `--exposures 0` was refused after 6 s of work, leaving
// captures/exposure_0.000000/ behind.
void CheckOptions(const NoiseStudyOptions& options) {
  if (options.capture_views < 0 || (options.capture_views != 0 && options.capture_views % 2 == 0)) {
    throw Error("noise study: --capture-views must be 0 (all) or odd, so the centre view stays the centre; got " +
                std::to_string(options.capture_views));
  }
  simulate::CheckRenderOptions(IdealRenderOptions(options));
  for (const double sigma : options.sigmas)
    if (!(sigma >= 0.0 && sigma <= 1.0)) throw Error("--sigmas: " + std::to_string(sigma) + " is not in [0, 1]");
  if (options.exposures.empty()) throw Error("--exposures: at least one exposure is needed (the reference)");
  for (const double exposure : options.exposures) {
    simulate::CaptureOptions capture;
    capture.exposure = exposure;
    try {
      simulate::CheckCaptureOptions(capture);
    } catch (const Error& error) {
      throw Error("--exposures: " + std::to_string(exposure) + ": " + error.what());
    }
  }
  (void)simulate::CameraPreset(options.camera);  // an unknown name throws
}

// The study itself, into the folder RunNoiseStudy made.
NoiseStudyResult RunNoiseStudyInto(const NoiseStudyOptions& options, const simulate::Scene& scene,
                                   const Stopwatch& stopwatch) {
  std::vector<Row> rows;
  Progress progress("noise study", options.sigmas.size() + options.exposures.size());

  // Image noise on the ideal light field.
  const simulate::RenderOptions render = IdealRenderOptions(options);
  simulate::RenderedLightField ideal = simulate::RenderLightField(scene, render);
  Trial clean;
  clean.gt_labels = ideal.labels;
  clean.gt_disparity = ideal.disparity;
  clean.gt_view_disparity = ideal.view_disparity;
  clean.size = options.size;
  for (std::size_t i = 0; i < options.sigmas.size(); ++i) {
    const double sigma = options.sigmas[i];
    spdlog::info("image noise sigma {}", sigma);
    Trial trial = clean;
    trial.light_field = ideal.light_field;
    simulate::AddGaussianNoise(trial.light_field, sigma, options.seed + i);
    for (auto& [method, metrics] : SegmentAndScore(trial, options.lsc))
      rows.push_back({"image", sigma, sigma, method, metrics});
    progress.Tick();
  }

  // Low light at the sensor, through decode.
  const simulate::CameraModel camera = simulate::CameraPreset(options.camera);
  const fs::path work = options.out / "captures";
  nlohmann::ordered_json brightness = nlohmann::ordered_json::array();
  for (double exposure : options.exposures) {
    const double photons = exposure * camera.full_well;
    spdlog::info("low light: exposure {} ({:.0f} photons at white)", exposure, photons);
    const Trial trial = LowLightTrial(options, exposure, work, work / "whites");
    nlohmann::ordered_json level = Brightness(trial.light_field);
    level["exposure"] = exposure;
    level["light_field"] = ToString(trial.light_field.shape());
    brightness.push_back(level);
    for (auto& [method, metrics] : SegmentAndScore(trial, options.lsc)) {
      metrics["photons_at_white"] = photons;
      rows.push_back({"lowlight", exposure, 1.0 / std::sqrt(photons), method, metrics});
    }
    progress.Tick();
  }
  progress.Finish();
  fs::remove_all(work);

  NoiseStudyResult result;
  WriteCsv(rows, options.out / "noise_study.csv");
  for (const auto& path : WritePlots(rows, "image", "Gaussian sigma", options.out)) result.plots.push_back(path);
  for (const auto& path : WritePlots(rows, "lowlight", "shot noise 1/sqrt(photons at white)", options.out))
    result.plots.push_back(path);

  nlohmann::ordered_json& summary = result.summary;
  summary["scene"] = options.scene;
  summary["ideal_light_field"] = ToString(ideal.light_field.shape());
  summary["camera"] = options.camera;
  summary["sigmas"] = options.sigmas;
  summary["exposures"] = options.exposures;
  summary["capture_views"] = options.capture_views;
  summary["lowlight_brightness"] = brightness;
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  for (const Row& row : rows)
    results.push_back({{"noise", row.noise}, {"level", row.level}, {"method", row.method}, {"metrics", row.metrics}});
  summary["results"] = results;
  summary["degradation"] = Degradation(rows);
  summary["files"] = {"noise_study.csv", "plot_<noise>_<metric>.png"};
  summary["wall_seconds"] = stopwatch.Seconds();
  stages::WriteJsonSummary(summary, options.out / "summary.json");
  return result;
}

}  // namespace

NoiseStudyResult RunNoiseStudy(const NoiseStudyOptions& options) {
  CheckOptions(options);
  const simulate::Scene scene = simulate::SceneFromSpec(options.scene);
  const Stopwatch stopwatch;
  std::error_code ec;
  const bool made_out = !fs::exists(options.out, ec);
  fs::create_directories(options.out);
  try {
    return RunNoiseStudyInto(options, scene, stopwatch);
  } catch (...) {
    // Nothing half-done stays: the captures' work folder always, the output folder if this run made it.
    fs::remove_all(made_out ? options.out : options.out / "captures", ec);
    throw;
  }
}

}  // namespace lfsp::noise_study
