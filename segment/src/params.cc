#include "lfsp/segment/params.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/core/noise.h"

namespace lfsp::segment {
namespace {

void Require(bool ok, const std::string& name, const std::string& expected) {
  if (!ok) throw Error("LFSP parameter " + name + ": expected " + expected);
}

template <typename T>
void ReadField(const nlohmann::json& json, const char* name, T& value, const std::string& where) {
  if (!json.contains(name)) return;
  const nlohmann::json& field = json.at(name);
  if (!field.is_number()) throw Error(where + ": field '" + name + "' must be a number");
  value = field.get<T>();
}

}  // namespace

nlohmann::json SegmentationRecord(const LfspParams& params, const std::string& disparity_source) {
  return {{"parameters", ToJson(params)}, {"disparity", disparity_source}};
}

nlohmann::json ToJson(const LfspParams& p) {
  return {{"size", p.size},
          {"lambda_p", p.lambda_p},
          {"lambda_d", p.lambda_d},
          {"lambda_s", p.lambda_s},
          {"lambda_b", p.lambda_b},
          {"pen_spatial", p.pen_spatial},
          {"pen_mixed", p.pen_mixed},
          {"pen_angular", p.pen_angular},
          {"colour_scale", p.colour_scale},
          {"slic_iterations", p.slic_iterations},
          {"iterations", p.iterations},
          {"plane_iterations", p.plane_iterations},
          {"inlier_threshold", p.inlier_threshold},
          {"hinge_penalty", p.hinge_penalty},
          {"occlusion_penalty", p.occlusion_penalty},
          {"impossible_penalty", p.impossible_penalty},
          {"convergence", p.convergence},
          {"presmooth", p.presmooth},
          {"threads", p.threads}};
}

LfspParams ParamsFromJson(const nlohmann::json& json, const std::string& where) {
  if (!json.is_object()) throw Error(where + ": LFSP parameters must be a JSON object");
  LfspParams p;
  ReadField(json, "size", p.size, where);
  ReadField(json, "lambda_p", p.lambda_p, where);
  ReadField(json, "lambda_d", p.lambda_d, where);
  ReadField(json, "lambda_s", p.lambda_s, where);
  ReadField(json, "lambda_b", p.lambda_b, where);
  ReadField(json, "pen_spatial", p.pen_spatial, where);
  ReadField(json, "pen_mixed", p.pen_mixed, where);
  ReadField(json, "pen_angular", p.pen_angular, where);
  ReadField(json, "colour_scale", p.colour_scale, where);
  ReadField(json, "slic_iterations", p.slic_iterations, where);
  ReadField(json, "iterations", p.iterations, where);
  ReadField(json, "plane_iterations", p.plane_iterations, where);
  ReadField(json, "inlier_threshold", p.inlier_threshold, where);
  ReadField(json, "hinge_penalty", p.hinge_penalty, where);
  ReadField(json, "occlusion_penalty", p.occlusion_penalty, where);
  ReadField(json, "impossible_penalty", p.impossible_penalty, where);
  ReadField(json, "convergence", p.convergence, where);
  ReadField(json, "presmooth", p.presmooth, where);
  ReadField(json, "threads", p.threads, where);
  Validate(p);
  return p;
}

void Validate(const LfspParams& p) {
  const auto finite_non_negative = [](double value) { return std::isfinite(value) && value >= 0.0; };
  Require(p.size >= 2 && p.size <= 1000, "size", "an integer in 2..1000");
  Require(finite_non_negative(p.lambda_p), "lambda_p", "a finite value >= 0");
  Require(finite_non_negative(p.lambda_d), "lambda_d", "a finite value >= 0");
  Require(finite_non_negative(p.lambda_s), "lambda_s", "a finite value >= 0");
  Require(finite_non_negative(p.lambda_b), "lambda_b", "a finite value >= 0");
  Require(finite_non_negative(p.pen_spatial), "pen_spatial", "a finite value >= 0");
  Require(finite_non_negative(p.pen_mixed), "pen_mixed", "a finite value >= 0");
  Require(finite_non_negative(p.pen_angular), "pen_angular", "a finite value >= 0");
  Require(std::isfinite(p.colour_scale) && p.colour_scale > 0.0, "colour_scale", "a finite value > 0");
  Require(p.slic_iterations >= 1 && p.slic_iterations <= 1000, "slic_iterations", "an integer in 1..1000");
  Require(p.iterations >= 0 && p.iterations <= 1000, "iterations", "an integer in 0..1000");
  Require(p.plane_iterations >= 0 && p.plane_iterations <= 1000, "plane_iterations", "an integer in 0..1000");
  Require(std::isfinite(p.inlier_threshold) && p.inlier_threshold > 0.0, "inlier_threshold", "a finite value > 0");
  Require(finite_non_negative(p.hinge_penalty), "hinge_penalty", "a finite value >= 0");
  Require(finite_non_negative(p.occlusion_penalty), "occlusion_penalty", "a finite value >= 0");
  Require(finite_non_negative(p.impossible_penalty), "impossible_penalty", "a finite value >= 0");
  Require(finite_non_negative(p.convergence), "convergence", "a finite value >= 0");
  Require(std::isfinite(p.presmooth) && p.presmooth <= 10.0, "presmooth", "a value <= 10 (negative = automatic)");
  Require(p.threads >= 0 && p.threads <= 1024, "threads", "an integer in 0..1024");
}

void RequireSuperpixelSizeFits(int size, const LightFieldShape& shape, const std::string& what) {
  const int shorter = std::min(shape.width, shape.height);
  if (size < 2 || size > shorter)
    throw Error(what + ": superpixel size " + std::to_string(size) + " does not fit views of " +
                std::to_string(shape.width) + "x" + std::to_string(shape.height) + " (expected 2.." +
                std::to_string(std::max(shorter, 2)) + ")");
}

double PresmoothForNoise(double noise_sigma) { return SmoothingForNoise(noise_sigma, 40.0, 1.5); }

}  // namespace lfsp::segment
