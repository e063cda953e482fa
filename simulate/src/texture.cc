#include "lfsp/simulate/texture.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <opencv2/core.hpp>
#include <vector>

#include "json_fields.h"
#include "lfsp/core/error.h"
#include "lfsp/core/file_names.h"
#include "lfsp/core/image_io.h"

namespace lfsp::simulate {
namespace {

Rgb Mix(const Rgb& a, const Rgb& b, float w) {
  return {a[0] + (b[0] - a[0]) * w, a[1] + (b[1] - a[1]) * w, a[2] + (b[2] - a[2]) * w};
}

// Integer hash -> [0, 1): a cheap, well-mixed lattice value for value noise (deterministic across platforms).
float LatticeValue(std::int32_t i, std::int32_t j, std::uint32_t seed) {
  std::uint32_t h =
      static_cast<std::uint32_t>(i) * 0x8da6b343u ^ static_cast<std::uint32_t>(j) * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

float Smooth(float f) { return f * f * (3.0f - 2.0f * f); }

// Value noise with smoothstep interpolation: smooth, band-limited to about 1/period.
float ValueNoise(float p, float q, std::uint32_t seed) {
  const float fp = std::floor(p);
  const float fq = std::floor(q);
  const auto i = static_cast<std::int32_t>(fp);
  const auto j = static_cast<std::int32_t>(fq);
  const float wx = Smooth(p - fp);
  const float wy = Smooth(q - fq);
  const float v00 = LatticeValue(i, j, seed);
  const float v10 = LatticeValue(i + 1, j, seed);
  const float v01 = LatticeValue(i, j + 1, seed);
  const float v11 = LatticeValue(i + 1, j + 1, seed);
  const float top = v00 + (v10 - v00) * wx;
  const float bottom = v01 + (v11 - v01) * wx;
  return top + (bottom - top) * wy;
}

Rgb SampleImage(const cv::Mat& image, float p, float q) {
  // Repeat the image over the plane; bilinear interpolation between pixel centres.
  const float x = (p - std::floor(p)) * static_cast<float>(image.cols) - 0.5f;
  const float y = (q - std::floor(q)) * static_cast<float>(image.rows) - 0.5f;
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  const float fx = x - static_cast<float>(x0);
  const float fy = y - static_cast<float>(y0);
  auto at = [&](int yy, int xx) {
    yy = (yy % image.rows + image.rows) % image.rows;
    xx = (xx % image.cols + image.cols) % image.cols;
    return image.at<cv::Vec3f>(yy, xx);
  };
  const cv::Vec3f c = at(y0, x0) * (1 - fx) * (1 - fy) + at(y0, x0 + 1) * fx * (1 - fy) +
                      at(y0 + 1, x0) * (1 - fx) * fy + at(y0 + 1, x0 + 1) * fx * fy;
  return {c[0], c[1], c[2]};
}

}  // namespace

Rgb Texture::Evaluate(float p, float q) const {
  switch (kind) {
    case Kind::kConstant:
      return colour_a;
    case Kind::kChecker: {
      const float c = angle == 0.0f ? 1.0f : std::cos(angle);  // the common unrotated case skips the trigonometry
      const float s = angle == 0.0f ? 0.0f : std::sin(angle);
      const float a = (c * p + s * q) / period;
      const float b = (-s * p + c * q) / period;
      const auto parity = (static_cast<long>(std::floor(a)) + static_cast<long>(std::floor(b))) & 1L;
      return parity != 0 ? colour_b : colour_a;
    }
    case Kind::kNoise: {
      // Two octaves: visible structure at `period` plus finer detail, so block matching has texture to work with.
      const float n = 0.7f * ValueNoise(p / period, q / period, seed) +
                      0.3f * ValueNoise(2.3f * p / period, 2.3f * q / period, seed + 7919u);
      return Mix(colour_a, colour_b, std::clamp(n, 0.0f, 1.0f));
    }
    case Kind::kStripes: {
      const float a = (std::cos(angle) * p + std::sin(angle) * q) / period;
      return (a - std::floor(a)) < 0.5f ? colour_a : colour_b;
    }
    case Kind::kGradient: {
      const float a = std::cos(angle) * p + std::sin(angle) * q;
      return Mix(colour_a, colour_b, std::clamp(a, 0.0f, 1.0f));
    }
    case Kind::kImage:
      return SampleImage(*image, p / period, q / period);
  }
  return colour_a;
}

namespace {

Texture::Kind KindFromName(const std::string& name, const std::string& where) {
  if (name == "constant") return Texture::Kind::kConstant;
  if (name == "checker") return Texture::Kind::kChecker;
  if (name == "noise") return Texture::Kind::kNoise;
  if (name == "stripes") return Texture::Kind::kStripes;
  if (name == "gradient") return Texture::Kind::kGradient;
  if (name == "image") return Texture::Kind::kImage;
  throw Error(where + ".type: unknown texture type '" + name +
              "' (expected constant, checker, noise, stripes, gradient or image)");
}

std::string KindName(Texture::Kind kind) {
  switch (kind) {
    case Texture::Kind::kConstant:
      return "constant";
    case Texture::Kind::kChecker:
      return "checker";
    case Texture::Kind::kNoise:
      return "noise";
    case Texture::Kind::kStripes:
      return "stripes";
    case Texture::Kind::kGradient:
      return "gradient";
    case Texture::Kind::kImage:
      return "image";
  }
  return "constant";
}

// Through ReadImage, like every image lfsp reads: the size the file declares is checked against its bytes before
// anything is allocated, and a missing, truncated or corrupt file is one lfsp::Error naming it (cv::imread allocated
// whatever a header declared, and libpng printed a line of its own for a truncated file).
std::shared_ptr<const cv::Mat> LoadImageTexture(const std::string& path, const std::string& where) {
  ImageFile file;
  try {
    file = ReadImage(path, ImageAlpha::kAsStored);  // alpha is ignored, so colour as stored (as cv::imread)
  } catch (const Error& error) {
    throw Error(where + ".path: " + error.what());
  }
  // RGB(A) or grey samples in [0, 1] (float files as stored): grey goes to all three channels, alpha is dropped.
  std::vector<cv::Mat> planes;
  cv::split(file.pixels, planes);
  const bool grey = planes.size() < 3;
  auto image = std::make_shared<cv::Mat>();
  cv::merge(std::vector<cv::Mat>{planes[0], planes[grey ? 0 : 1], planes[grey ? 0 : 2]}, *image);
  // A JPEG photo is turned upright by its Exif orientation, as cv::imread did (OpenImageIO leaves it as stored).
  const std::string extension = LowerExtension(path);
  if (extension == ".jpg" || extension == ".jpeg") {
    cv::Mat& m = *image;
    const int orientation = file.orientation;
    if (orientation >= 5 && orientation <= 8) cv::transpose(m, m);
    if (orientation == 2 || orientation == 6) cv::flip(m, m, 1);  // horizontally
    if (orientation == 3 || orientation == 7) cv::flip(m, m, -1);
    if (orientation == 4 || orientation == 8) cv::flip(m, m, 0);  // vertically
  }
  return image;
}

}  // namespace

Texture TextureFromJson(const nlohmann::json& json, const std::string& base_dir, const std::string& where) {
  Texture texture;
  if (!json.is_object()) throw Error(where + ": expected an object");
  texture.kind = KindFromName(RequireString(json, "type", where), where);
  if (json.contains("colour")) texture.colour_a = texture.colour_b = ReadRgb(json.at("colour"), where + ".colour");
  if (json.contains("colours")) {
    const auto& colours = json.at("colours");
    if (!colours.is_array() || colours.size() != 2) throw Error(where + ".colours: expected two [r,g,b] colours");
    texture.colour_a = ReadRgb(colours[0], where + ".colours[0]");
    texture.colour_b = ReadRgb(colours[1], where + ".colours[1]");
  }
  texture.period = ReadFloat(json, "period", texture.kind == Texture::Kind::kImage ? 1.0f : 0.1f, where);
  if (!(texture.period > 0.0f)) throw Error(where + ".period: must be > 0");
  texture.angle = ReadFloat(json, "angle", 0.0f, where) * std::numbers::pi_v<float> / 180.0f;
  const float seed = ReadFloat(json, "seed", 1.0f, where);
  if (seed < 0.0f) throw Error(where + ".seed: must be >= 0");
  texture.seed = static_cast<std::uint32_t>(seed);
  if (texture.kind == Texture::Kind::kImage) {
    texture.image_path = RequireString(json, "path", where);
    std::filesystem::path path(texture.image_path);
    if (path.is_relative()) path = std::filesystem::path(base_dir) / path;
    texture.image = LoadImageTexture(path.string(), where);
  }
  return texture;
}

nlohmann::json TextureToJson(const Texture& texture) {
  nlohmann::json json;
  json["type"] = KindName(texture.kind);
  if (texture.kind == Texture::Kind::kConstant) {
    json["colour"] = texture.colour_a;
  } else if (texture.kind != Texture::Kind::kImage) {
    json["colours"] = {texture.colour_a, texture.colour_b};
  }
  json["period"] = texture.period;
  json["angle"] = texture.angle * 180.0f / std::numbers::pi_v<float>;
  json["seed"] = texture.seed;
  if (texture.kind == Texture::Kind::kImage) json["path"] = texture.image_path;
  return json;
}

}  // namespace lfsp::simulate
