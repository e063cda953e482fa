#include "stage_bindings.h"

#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "arguments/decode_arguments.h"
#include "arguments/depth_arguments.h"
#include "arguments/evaluate_arguments.h"
#include "arguments/recolor_arguments.h"
#include "arguments/refocus_arguments.h"
#include "arguments/segment_arguments.h"
#include "arguments/simulate_arguments.h"
#include "keyword_options.h"
#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/shear.h"
#include "lfsp/core/view_crop.h"
#include "lfsp/depth/metrics.h"
#include "lfsp/depth/region_metrics.h"
#include "lfsp/edit/recolor.h"
#include "lfsp/edit/refocus.h"
#include "lfsp/edit/selection.h"
#include "lfsp/segment/lfsp.h"
#include "lfsp/simulate/simulate.h"
#include "light_field_binding.h"
#include "long_work.h"
#include "numpy_arrays.h"
#include "raw_input_options.h"
#include "stages/decode_stage.h"
#include "stages/evaluate_stage.h"
#include "stages/grid_stage.h"
#include "stages/refocus_stage.h"
#include "view_selection.h"

namespace lfsp::python {
namespace {

py::object JsonToPython(const nlohmann::json& json) { return py::module_::import("json").attr("loads")(json.dump()); }

std::string PathText(py::handle path) { return py::module_::import("os").attr("fspath")(path).cast<std::string>(); }

// The docstring of a function: what it does, then its keyword options as `lfsp` documents them.
std::string Doc(const std::string& summary, const OptionAdder& options) {
  return summary + "\n\nKeyword options (the command line's --option-name, written option_name):\n" +
         KeywordHelp(options);
}

DisparityMap DisparityOrOwn(py::handle disparity, const Bundle& light_field, const std::string& function) {
  if (!disparity.is_none()) return DisparityFromArray(disparity, "disparity");
  if (light_field.disparity) return *light_field.disparity;
  throw Error(function + ": the light field carries no disparity; pass disparity=");
}

// --- read / write ------------------------------------------------------------------------------------------------

void BindReadWrite(py::module_& m) {
  m.def(
      "read",
      [](py::object path, const std::string& views_pattern, int eslf_nu, int eslf_nv) {
        LoadOptions options;
        options.views_pattern = views_pattern;
        if (eslf_nu > 0) options.eslf.nu = eslf_nu;
        if (eslf_nv > 0) options.eslf.nv = eslf_nv;
        const std::string name = PathText(path);
        return ToPython(RunLongWork([&] { return LoadLightField(name, options); }));
      },
      py::arg("path"), py::kw_only(), py::arg("views_pattern") = "", py::arg("eslf_nu") = 0, py::arg("eslf_nv") = 0,
      R"doc(read(path, *, views_pattern="", eslf_nu=0, eslf_nv=0) -> LightField

Reads any light field `lfsp` reads: a views folder (HCI input_Cam###.png, <row>_<col>.png, LFToolbox and
other namings, or views_pattern such as '{row}_{col}.png'), an .h5 bundle (or the old HCI lf.h5), an ESLF .png
(eslf_nu / eslf_nv: its angular size when the file does not record it) or a .mat light field (LFToolbox v5 / v7.3,
or the [U, V, H, W, 3] 'LF' layout). A ground-truth disparity and labels that come with it are attached.
Raises lfsp.Error naming the file for anything it cannot read.)doc");
  m.def(
      "write",
      [](const Bundle& light_field, py::object path, int bit_depth, const std::string& view_format) {
        if (bit_depth != 8 && bit_depth != 16) throw Error("bit_depth: expected 8 or 16");
        if (view_format != "png" && view_format != "tif")
          throw Error("view_format: expected png or tif, not " + view_format);
        const std::string name = PathText(path);
        RunLongWork([&] { SaveLightField(light_field, name, bit_depth, "." + view_format); });
      },
      py::arg("light_field"), py::arg("path"), py::kw_only(), py::arg("bit_depth") = 8, py::arg("view_format") = "png",
      R"doc(write(light_field, path, *, bit_depth=8, view_format="png")

Writes a light field in the format its path names: OUT.h5 a bundle (float32, exact, with its disparity and
labels), OUT.png an ESLF image, OUT.mat LFToolbox's LF(v, u, y, x, c) with a weight channel, anything else a views
folder (bit_depth 8 or 16, view_format png or tif). Written atomically: nothing is half-written on failure.)doc");
  m.def(
      "read_disparity", [](py::object path) { return ToArray(ReadPfm(PathText(path))); }, py::arg("path"),
      "read_disparity(path) -> (H, W) float32\n\nReads a disparity map (PFM, HCI convention, as `lfsp depth` writes "
      "it) as an (H, W) float32 array.");
  m.def(
      "write_disparity",
      [](py::object disparity, py::object path) {
        const std::string name = PathText(path);
        const DisparityMap map = DisparityFromArray(disparity, "disparity");
        if (std::filesystem::path(name).extension() == ".png")
          WriteDisparityPng16(map, name);
        else
          WritePfm(map, name);
      },
      py::arg("disparity"), py::arg("path"),
      "write_disparity(disparity, path)\n\nWrites an (H, W) disparity map: PATH.png as a 16-bit PNG with its range in "
      "the PNG's text (as `lfsp convert` "
      "writes it), anything else as PFM (float32, exact; HCI convention).");
}

// --- decode / grid -------------------------------------------------------------------------------------------------

void BindDecode(py::module_& m) {
  const auto decode_options = [](cli::DecodeArguments& a) {
    return [&a](CLI::App* app) { cli::AddDecodeArguments(app, a); };
  };
  cli::DecodeArguments defaults;
  m.def(
      "decode",
      [decode_options](py::object capture, const py::kwargs& keywords) {
        cli::DecodeArguments arguments;
        ParseKeywords("decode", keywords, decode_options(arguments));
        const decode::CaptureDecodeOptions options = cli::ToCaptureDecodeOptions(arguments);
        const std::string path = PathText(capture);
        return ToPython(RunLongWork([&] { return stages::RunDecodeStage(path, options).bundle; }));
      },
      py::arg("capture"),
      Doc("decode(capture, **options) -> LightField\n\nDecodes a Lytro raw capture (.lfp/.lfr/.LFR, .RAW + "
          ".TXT/.json, or a plain raw image with camera=) into a light field with per-ray weights, as `lfsp decode` "
          "does (white image by serial/zoom/focus, or estimated from the capture; lenslet grid; hot pixels; "
          "devignetting; demosaic; hex->rect slicing; colour). Samples are rounded as a bundle stores them, so "
          "later stages compute what they compute on a written file.",
          decode_options(defaults))
          .c_str());

  cli::PlainRawArguments plain_defaults;
  std::string kind_default = "auto";
  const auto grid_options = [](std::string& kind, cli::PlainRawArguments& plain) {
    return [&kind, &plain](CLI::App* app) {
      app->add_option("--kind", kind,
                      "auto | white | capture: how to fit (white: per-lens centroids; capture: lattice periodicity, "
                      "robust to scene content; auto: Lytro white images as white, Lytro captures as capture, "
                      "plain images by how evenly lit their micro-images are)")
          ->capture_default_str();
      cli::AddPlainRawOptions(app, plain);
    };
  };
  m.def(
      "grid",
      [grid_options](py::object input, const py::kwargs& keywords) {
        std::string kind = "auto";
        cli::PlainRawArguments plain;
        ParseKeywords("grid", keywords, grid_options(kind, plain));
        const std::string path = PathText(input);
        const stages::GridStageResult result =
            RunLongWork([&] { return stages::RunGridStage(path, kind, cli::ToPlainRawOptions(plain)); });
        py::dict document = JsonToPython(result.document);
        const decode::LensletGrid& grid = result.grid;
        py::array_t<double> centres({grid.rows, grid.columns, 2});
        auto c = centres.mutable_unchecked<3>();
        for (int j = 0; j < grid.rows; ++j)
          for (int i = 0; i < grid.columns; ++i) grid.Centre(i, j, c(j, i, 0), c(j, i, 1));
        document["centres"] = centres;
        return document;
      },
      py::arg("input"),
      Doc("grid(input, **options) -> dict\n\nThe lenslet lattice of a white image or an ordinary capture, as `lfsp "
          "grid` writes it (input, format, metadata, kind, grid: spacing, rotation, origin, lens counts, fit), plus "
          "'centres': every lens centre as an array (rows, columns, 2) of (x, y) in 0-based pixel coordinates.",
          grid_options(kind_default, plain_defaults))
          .c_str());
}

// --- depth / segment -----------------------------------------------------------------------------------------------

void BindDepthAndSegment(py::module_& m) {
  const auto depth_options = [](int& views, cli::DepthArguments& a) {
    return [&views, &a](CLI::App* app) {
      cli::AddViewsOption(app, views);
      cli::AddDepthArguments(app, a);
    };
  };
  int views_default = 0;
  cli::DepthArguments depth_defaults;
  m.def(
      "depth",
      [depth_options](const Bundle& light_field, const py::kwargs& keywords) {
        int views = 0;
        cli::DepthArguments arguments;
        ParseKeywords("depth", keywords, depth_options(views, arguments));
        const depth::DepthOptions options = cli::ToDepthOptions(arguments);
        Bundle storage;
        const Bundle& chosen = ChosenViews(light_field, views, storage);
        depth::DepthResult result = RunLongWork([&] { return depth::EstimateDepth(chosen.light_field, options); });
        return py::make_tuple(ToArray(std::move(result.disparity)), ToArray(std::move(result.confidence)));
      },
      py::arg("light_field"),
      Doc("depth(light_field, **options) -> (disparity, confidence)\n\nOcclusion-aware centre-view disparity, as "
          "`lfsp depth` computes it: disparity (H, W) float32 in pixels per view step (HCI convention) and its "
          "confidence in [0, 1].",
          depth_options(views_default, depth_defaults))
          .c_str());

  const auto segment_options = [](int& views, segment::LfspParams& params) {
    return [&views, &params](CLI::App* app) {
      cli::AddViewsOption(app, views);
      cli::AddLfspParameters(app, params);
    };
  };
  segment::LfspParams params_default;
  m.def(
      "segment",
      [segment_options](const Bundle& light_field, py::object disparity, const py::kwargs& keywords) {
        int views = 0;
        segment::LfspParams params;
        ParseKeywords("segment", keywords, segment_options(views, params));
        segment::Validate(params);
        const DisparityMap map = DisparityOrOwn(disparity, light_field, "segment");
        Bundle storage;
        const Bundle& chosen = ChosenViews(light_field, views, storage);
        segment::LfspResult result =
            RunLongWork([&] { return segment::SegmentLightField(chosen.light_field, map, params); });
        return ToArray(std::move(result.labels));
      },
      py::arg("light_field"), py::arg("disparity") = py::none(),
      Doc("segment(light_field, disparity=None, **params) -> labels\n\nLight-field superpixels (LFSP, Zhu et al. "
          "TIP 2020) as `lfsp segment` computes them: labels (nv, nu, H, W) int32 for every ray of the chosen views, "
          "each label one centre-view superpixel projected consistently to all views. disparity: the centre-view "
          "disparity (H, W) to segment with (default: the light field's own).",
          segment_options(views_default, params_default))
          .c_str());
}

// --- evaluate ------------------------------------------------------------------------------------------------------

void BindEvaluate(py::module_& m) {
  const auto scoring_options = [](cli::SegmentationEvaluationArguments& scoring, segment::LfspParams& params) {
    return [&scoring, &params](CLI::App* app) {
      cli::AddSegmentationEvaluationArguments(app, scoring);
      cli::AddLfspParameters(app, params);
    };
  };
  cli::SegmentationEvaluationArguments scoring_defaults;
  segment::LfspParams params_default;
  m.def(
      "evaluate_segmentation",
      [scoring_options](py::object labels_array, py::object light_field, py::object disparity, py::object gt_disparity,
                        py::object gt_labels, const py::kwargs& keywords) {
        cli::SegmentationEvaluationArguments scoring;
        segment::EvaluationOptions options;
        ParseKeywords("evaluate_segmentation", keywords, scoring_options(scoring, options.lfsp));
        const segment::LfspParams params = options.lfsp;
        options = cli::ToEvaluationOptions(scoring);
        options.lfsp = params;
        const Labels labels = LabelsFromArray(labels_array, "labels");
        const Bundle* lf = light_field.is_none() ? nullptr : &light_field.cast<const Bundle&>();
        Bundle central_views;  // labels made on the well-lit central views (as segment chooses them) score those
        if (lf != nullptr && ViewsForLabels(0, lf->light_field.shape(), labels.shape()) > 0)
          lf = &ChosenViews(*lf, labels.shape().nu, central_views);
        if (lf != nullptr) RequireLabelsMatch(labels, lf->light_field.shape(), "labels");
        std::optional<DisparityMap> segmentation_disparity, truth_disparity;
        if (!disparity.is_none()) segmentation_disparity = DisparityFromArray(disparity, "disparity");
        if (!gt_disparity.is_none()) truth_disparity = DisparityFromArray(gt_disparity, "gt_disparity");
        std::optional<Labels> truth_labels;
        if (!gt_labels.is_none()) truth_labels = LabelsFromArray(gt_labels, "gt_labels");
        // Explicit LFSP keywords win over the parameters a segmentation bundle's metadata records.
        segment::LfspParams scratch;
        const bool use_recorded = !AnyKeywordOf(keywords, [&](CLI::App* app) { cli::AddLfspParameters(app, scratch); });
        const stages::GroundTruth truth{truth_disparity ? &*truth_disparity : nullptr,
                                        truth_labels ? &*truth_labels : nullptr};
        const nlohmann::json report = RunLongWork([&] {
          return stages::EvaluateSegmentationParts(lf ? &lf->light_field : nullptr, labels,
                                                   segmentation_disparity ? &*segmentation_disparity : nullptr, truth,
                                                   options, "light_field", use_recorded);
        });
        return JsonToPython(report);
      },
      py::arg("labels"), py::kw_only(), py::arg("light_field") = py::none(), py::arg("disparity") = py::none(),
      py::arg("gt_disparity") = py::none(), py::arg("gt_labels") = py::none(),
      Doc("evaluate_segmentation(labels, *, light_field=None, disparity=None, gt_disparity=None, gt_labels=None, "
          "**options) -> dict\n\nEvery superpixel metric of a light-field segmentation, the same numbers as `lfsp "
          "evaluate segmentation` prints: boundary recall, under-segmentation error, ASA, compactness (with "
          "gt_labels, per-ray object labels), LFSP self-similarity and labels per pixel (with gt_disparity, the "
          "true centre-view disparity), effective label ratio, and the refocus sweep (LFSP re-run on the light "
          "field refocused; needs light_field and the disparity the labels were made with; re-run with the LFSP "
          "keywords below, or the parameters recorded in a segmentation bundle's metadata).",
          scoring_options(scoring_defaults, params_default))
          .c_str());

  depth::MetricOptions metric_defaults;
  const auto metric_options = [](depth::MetricOptions& metrics) {
    return [&metrics](CLI::App* app) { cli::AddDepthMetricArguments(app, metrics); };
  };
  m.def(
      "evaluate_depth",
      [metric_options](py::object disparity, py::object gt_disparity, py::object confidence, const std::string& masks,
                       const py::kwargs& keywords) {
        depth::MetricOptions metrics;
        ParseKeywords("evaluate_depth", keywords, metric_options(metrics));
        const DisparityMap algo = DisparityFromArray(disparity, "disparity");
        const DisparityMap gt = DisparityFromArray(gt_disparity, "gt_disparity");
        std::optional<DisparityMap> confidence_map;
        if (!confidence.is_none()) confidence_map = DisparityFromArray(confidence, "confidence");
        if (!masks.empty() && !std::filesystem::is_directory(masks)) throw Error(masks + ": masks is not a folder");
        const depth::EvaluationMasks regions =
            masks.empty() ? depth::DeriveEvaluationMasks(gt, metrics) : depth::ReadEvaluationMasks(masks, gt, metrics);
        return JsonToPython(depth::ToJson(
            depth::EvaluateDisparity(algo, gt, metrics, regions, confidence_map ? &*confidence_map : nullptr)));
      },
      py::arg("disparity"), py::arg("gt_disparity"), py::kw_only(), py::arg("confidence") = py::none(),
      py::arg("masks") = "",
      Doc("evaluate_depth(disparity, gt_disparity, *, confidence=None, masks='', **options) -> dict\n\nHCI 4D "
          "light-field benchmark metrics of a centre-view disparity, as `lfsp evaluate depth` prints them: MSE x100, "
          "BadPix 0.07 / 0.03 / 0.01 (%), Q25, over all pixels and near ground-truth discontinuities; the fattening "
          "index; bumpiness on planes and smooth surfaces; with `confidence` (an (H, W) array, larger = more "
          "trusted), its sparsification curve. `masks`: a folder with the benchmark's mask_discontinuities.png, "
          "mask_planes.png, mask_smooth_surfaces.png (default: regions derived from the ground truth).",
          metric_options(metric_defaults))
          .c_str());
}

// --- recolor / refocus / shear -------------------------------------------------------------------------------------

std::vector<std::int32_t> Selection(const Labels& labels, py::object label_ids, py::object at, py::object mask) {
  const int ways = (label_ids.is_none() ? 0 : 1) + (at.is_none() ? 0 : 1) + (mask.is_none() ? 0 : 1);
  if (ways != 1) throw Error("recolor: choose the superpixels in exactly one way: label_ids, at or mask");
  if (!label_ids.is_none()) return edit::SelectLabelIds(labels, label_ids.cast<std::vector<std::int32_t>>());
  if (!at.is_none()) {
    std::vector<cv::Point> points;
    for (const py::handle point : at) {
      if (py::isinstance<py::str>(point)) {
        points.push_back(edit::ParseViewPoint(point.cast<std::string>(), "at"));
      } else {
        const auto xy = point.cast<std::vector<int>>();
        if (xy.size() != 2) throw Error("at: expected (x, y) points");
        points.emplace_back(xy[0], xy[1]);
      }
    }
    return edit::SelectAtPoints(labels, points);
  }
  return edit::SelectByMask(labels, MaskFromArray(mask, "mask"), 0.5);
}

void BindEdits(py::module_& m) {
  const auto recolor_options = [](int& views, cli::RecolorArguments& a) {
    return [&views, &a](CLI::App* app) {
      cli::AddViewsOption(app, views);
      cli::AddRecolorArguments(app, a);
    };
  };
  int views_default = 0;
  cli::RecolorArguments recolor_defaults;
  m.def(
      "recolor",
      [recolor_options](const Bundle& light_field, py::object labels, py::object label_ids, py::object at,
                        py::object mask, const py::kwargs& keywords) {
        int views = 0;
        cli::RecolorArguments arguments;
        ParseKeywords("recolor", keywords, recolor_options(views, arguments));
        const edit::RecolorOptions options = cli::ToRecolorOptions(arguments);
        std::optional<Labels> given;
        if (!labels.is_none()) given = LabelsFromArray(labels, "labels");
        const std::optional<Labels>& chosen_labels = given ? given : light_field.labels;
        if (!chosen_labels) throw Error("recolor: the light field carries no labels; pass labels=");
        // Labels made on the well-lit central views (as segment chooses them) select the same views here; the input
        // is never modified, and only the views kept are copied.
        const int requested = ViewsForLabels(views, light_field.light_field.shape(), chosen_labels->shape());
        const int n = ChooseViews(light_field.light_field, requested).n;
        Bundle edited = CentralViewsOf(light_field, n);
        if (given) edited.labels = given->shape().nu == n && given->shape().nv == n ? *given : CentralViews(*given, n);
        RequireLabelsMatch(*edited.labels, edited.light_field.shape(), "labels");
        const std::vector<std::int32_t> selection = Selection(*edited.labels, label_ids, at, mask);
        RunLongWork([&] { edit::Recolor(edited.light_field, *edited.labels, selection, options); });
        return ToPython(std::move(edited));
      },
      py::arg("light_field"), py::kw_only(), py::arg("labels") = py::none(), py::arg("label_ids") = py::none(),
      py::arg("at") = py::none(), py::arg("mask") = py::none(),
      Doc("recolor(light_field, *, labels=None, label_ids=None, at=None, mask=None, **options) -> LightField\n\n"
          "Recolours superpixels in every view at once, as `lfsp recolor` does: a new light field (the input is "
          "not changed) whose rays outside the selection and its feather band are bit-identical. labels: per-ray "
          "labels (default: the light field's own). Choose the superpixels in exactly one way: label_ids (a list "
          "of ids), at (centre-view points (x, y) or 'x,y' strings) or mask (H x W, nonzero = inside; labels with "
          "more than half their centre-view area inside).",
          recolor_options(views_default, recolor_defaults))
          .c_str());

  const auto refocus_options = [](int& views, cli::RefocusArguments& a) {
    return [&views, &a](CLI::App* app) {
      cli::AddViewsOption(app, views);
      cli::AddRefocusArguments(app, a);
    };
  };
  cli::RefocusArguments refocus_defaults;
  m.def(
      "refocus",
      [refocus_options](const Bundle& light_field, py::object disparities, const py::kwargs& keywords) {
        int views = 0;
        cli::RefocusArguments arguments;
        ParseKeywords("refocus", keywords, refocus_options(views, arguments));
        const edit::RefocusOptions options = cli::ToRefocusOptions(arguments);
        const bool many = py::isinstance<py::list>(disparities) || py::isinstance<py::tuple>(disparities);
        const std::vector<float> levels =
            many ? disparities.cast<std::vector<float>>() : std::vector<float>{disparities.cast<float>()};
        for (const float d : levels) cli::RequireRefocusDisparity(d, "disparity");
        Bundle storage;
        const Bundle& chosen = ChosenViews(light_field, views, storage);
        const std::vector<cv::Mat> slices =
            RunLongWork([&] { return edit::FocalStack(chosen.light_field, levels, options); });
        if (!many) return py::object(ImageToArray(slices.front()));
        py::list images;
        for (const cv::Mat& slice : slices) images.append(ImageToArray(slice));
        return py::object(images);
      },
      py::arg("light_field"), py::arg("disparity"),
      Doc("refocus(light_field, disparity, **options) -> image or list of images\n\nShift-and-sum refocusing as "
          "`lfsp refocus` does it: the image (H, W, 3) float32 focused at `disparity` (pixels per view step; a "
          "list gives a focal stack), in the light field's transfer.",
          refocus_options(views_default, refocus_defaults))
          .c_str());

  m.def(
      "all_in_focus",
      [](const Bundle& light_field, py::object disparity, bool no_occlusion, bool no_weights, int views) {
        const DisparityMap map = DisparityOrOwn(disparity, light_field, "all_in_focus");
        edit::AllInFocusOptions options;
        options.occlusion_aware = !no_occlusion;
        options.use_ray_weights = !no_weights;
        Bundle storage;
        const Bundle& chosen = ChosenViews(light_field, views, storage);
        return ImageToArray(RunLongWork([&] { return edit::AllInFocus(chosen.light_field, map, options); }));
      },
      py::arg("light_field"), py::arg("disparity") = py::none(), py::kw_only(), py::arg("no_occlusion") = false,
      py::arg("no_weights") = false, py::arg("views") = 0,
      "all_in_focus(light_field, disparity=None, *, no_occlusion=False, no_weights=False, views=0) -> image\n\n"
      "Every centre-view pixel focused at its own disparity (default: the light field's own), leaving out rays "
      "that something nearer hides (no_occlusion=True: use them), as `lfsp refocus --all-in-focus`.");

  m.def(
      "shear",
      [](const Bundle& light_field, float disparity, const std::string& interpolation) {
        cli::RequireRefocusDisparity(disparity, "disparity");
        ShearOptions options;
        options.interpolation = stages::InterpolationFromName(interpolation);
        Bundle sheared;
        sheared.light_field = RunLongWork([&] { return ShearLightField(light_field.light_field, disparity, options); });
        if (light_field.labels) sheared.labels = ShearLabels(*light_field.labels, disparity);
        if (light_field.disparity) sheared.disparity = ShearDisparity(*light_field.disparity, disparity);
        return ToPython(std::move(sheared));
      },
      py::arg("light_field"), py::arg("disparity"), py::kw_only(), py::arg("interpolation") = "linear",
      "shear(light_field, disparity, *, interpolation='linear') -> LightField\n\nThe light field sheared by "
      "`disparity` pixels per view step (points at that disparity become aligned; every disparity decreases by it), "
      "as `lfsp refocus --shear` writes it: weights mark rays that came from outside a view; labels and disparity "
      "are sheared along. interpolation: linear or cubic.");
}

// --- simulate ------------------------------------------------------------------------------------------------------

void BindSimulate(py::module_& m) {
  const auto simulate_options = [](cli::SimulateArguments& a) {
    return [&a](CLI::App* app) { cli::AddSimulateArguments(app, a); };
  };
  cli::SimulateArguments defaults;
  m.def(
      "_simulate",
      [simulate_options](py::object out, const py::kwargs& keywords) {
        cli::SimulateArguments arguments;
        ParseKeywords("simulate", keywords, simulate_options(arguments));
        const simulate::SimulateOptions options = cli::ToSimulateOptions(arguments);
        const std::string folder = PathText(out);
        return JsonToPython(RunLongWork([&] { return simulate::Simulate(options, folder).summary; }));
      },
      py::arg("out"));
  m.attr("_simulate_keywords") = KeywordHelp(simulate_options(defaults));
}

}  // namespace

void BindStages(py::module_& module) {
  BindReadWrite(module);
  BindDecode(module);
  BindDepthAndSegment(module);
  BindEvaluate(module);
  BindEdits(module);
  BindSimulate(module);
}

}  // namespace lfsp::python
