#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <string>

namespace lfsp::simulate {

// An RGB colour with components in [0, 1] (display values, i.e. sRGB-encoded).
using Rgb = std::array<float, 3>;

// A surface texture, evaluated at normalised surface coordinates (p, q): for planes these are the centre-view image
// position divided by the image size (so a texture scales with the rendered resolution), for ellipsoids the
// position on the silhouette disc. Procedural kinds are cheap enough to evaluate per ray.
struct Texture {
  enum class Kind { kConstant, kChecker, kNoise, kStripes, kGradient, kImage };
  Kind kind = Kind::kConstant;
  Rgb colour_a{0.5f, 0.5f, 0.5f};        // constant colour, or the first of two colours
  Rgb colour_b{0.5f, 0.5f, 0.5f};        // second colour (checker, noise, stripes, gradient)
  float period = 0.1f;                   // checker cell / stripe period / noise feature size, in normalised units
  float angle = 0.0f;                    // stripes and gradient direction, radians from the +x axis
  std::uint32_t seed = 1;                // noise pattern
  std::string image_path;                // kImage: a PNG (or any image ReadImage reads) mapped onto [0,1]^2
  std::shared_ptr<const cv::Mat> image;  // kImage: CV_32FC3 RGB in [0, 1], loaded once

  Rgb Evaluate(float p, float q) const;
};

// JSON form, e.g. {"type": "checker", "colours": [[1,0,0],[0,0,1]], "period": 0.05}.
// Types: constant (colour), checker, noise, stripes (angle in degrees), gradient, image (path relative to
// `base_dir`). Throws lfsp::Error naming `where` for a bad field.
Texture TextureFromJson(const nlohmann::json& json, const std::string& base_dir, const std::string& where);
nlohmann::json TextureToJson(const Texture& texture);

}  // namespace lfsp::simulate
