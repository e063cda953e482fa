#include "lfsp/core/eslf.h"

#include <opencv2/core.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"

namespace lfsp {
namespace {

int AngularFromText(const ImageFile& image, const char* key, std::optional<int> given, const std::string& path) {
  if (given) return *given;
  const auto found = image.text.find(key);
  if (found == image.text.end())
    ThrowFileError(path, std::string("ESLF angular size unknown: no ") + key +
                             " attribute in the file; pass it explicitly (the Stanford Lytro archive uses 14x14)");
  try {
    return std::stoi(found->second);
  } catch (const std::exception&) {
    ThrowFileError(path, std::string("bad ") + key + " attribute '" + found->second + "'");
  }
}

}  // namespace

LightField ReadEslf(const std::filesystem::path& path, const EslfOptions& options) {
  const std::string name = path.string();
  const ImageFile image = ReadImage(path);
  const int nu = AngularFromText(image, "lfsp:nu", options.nu, name);
  const int nv = AngularFromText(image, "lfsp:nv", options.nv, name);
  if (nu <= 0 || nv <= 0 || nu > 64 || nv > 64) ThrowFileError(name, "ESLF angular size out of range");
  if (image.pixels.cols % nu != 0 || image.pixels.rows % nv != 0)
    ThrowFileError(name, "image " + std::to_string(image.pixels.cols) + "x" + std::to_string(image.pixels.rows) +
                             " is not a whole number of " + std::to_string(nu) + "x" + std::to_string(nv) +
                             " macro-pixels");
  LightFieldShape shape;
  shape.nu = nu;
  shape.nv = nv;
  shape.width = image.pixels.cols / nu;
  shape.height = image.pixels.rows / nv;
  shape.channels = std::min(image.pixels.channels(), 3);
  LightField light_field(shape);
  const auto transfer = image.text.find("lfsp:transfer");
  light_field.transfer = transfer != image.text.end()
                             ? TransferFromFile(transfer->second, name, "text chunk lfsp:transfer")
                             : Transfer::kSrgb;

  const int source_channels = image.pixels.channels();
  const int channels = shape.channels;
#pragma omp parallel for
  for (int row = 0; row < image.pixels.rows; ++row) {
    const int y = row / nv;
    const int v = row % nv;
    const float* source = image.pixels.ptr<float>(row);
    for (int column = 0; column < image.pixels.cols; ++column) {
      const int x = column / nu;
      const int u = column % nu;
      float* destination = &light_field.at({u, v}, y, x, 0);
      for (int c = 0; c < channels; ++c) destination[c] = source[column * source_channels + c];
    }
  }
  return light_field;
}

void WriteEslf(const LightField& light_field, const std::filesystem::path& path, const EslfOptions& options) {
  const LightFieldShape& shape = light_field.shape();
  if (options.nu && *options.nu != shape.nu) throw Error("ESLF nu option disagrees with the light field");
  if (options.nv && *options.nv != shape.nv) throw Error("ESLF nv option disagrees with the light field");
  cv::Mat image(shape.height * shape.nv, shape.width * shape.nu, CV_MAKETYPE(CV_32F, shape.channels));
  const int channels = shape.channels;
#pragma omp parallel for
  for (int row = 0; row < image.rows; ++row) {
    const int y = row / shape.nv;
    const int v = row % shape.nv;
    float* destination = image.ptr<float>(row);
    for (int column = 0; column < image.cols; ++column) {
      const float* source = &light_field.at({column % shape.nu, v}, y, column / shape.nu, 0);
      for (int c = 0; c < channels; ++c) destination[column * channels + c] = source[c];
    }
  }
  WriteImage(image, path, options.bit_depth,
             {{"lfsp:nu", std::to_string(shape.nu)},
              {"lfsp:nv", std::to_string(shape.nv)},
              {"lfsp:transfer", ToString(light_field.transfer)}});
}

}  // namespace lfsp
