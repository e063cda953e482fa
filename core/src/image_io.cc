#include "lfsp/core/image_io.h"

#include <OpenImageIO/imageio.h>

#include <opencv2/core.hpp>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"

namespace lfsp {
namespace {

OIIO::TypeDesc StorageType(int bit_depth) {
  switch (bit_depth) {
    case 8:
      return OIIO::TypeDesc::UINT8;
    case 16:
      return OIIO::TypeDesc::UINT16;
    case 32:
      return OIIO::TypeDesc::FLOAT;
    default:
      throw Error("unsupported bit depth " + std::to_string(bit_depth) + " (expected 8, 16 or 32)");
  }
}

OIIO::TypeDesc MatType(int depth) {
  switch (depth) {
    case CV_8U:
      return OIIO::TypeDesc::UINT8;
    case CV_16U:
      return OIIO::TypeDesc::UINT16;
    case CV_32F:
      return OIIO::TypeDesc::FLOAT;
    default:
      throw Error("cannot write images of OpenCV depth " + std::to_string(depth));
  }
}

}  // namespace

ImageFile ReadImage(const std::filesystem::path& path) {
  const std::string name = path.string();
  auto input = OIIO::ImageInput::open(name);
  if (!input) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "cannot open image";
    ThrowFileError(name, why);
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.nchannels > 4)
    ThrowFileError(name, "unsupported image layout " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                             "x" + std::to_string(spec.nchannels));
  ImageFile image;
  image.bit_depth = static_cast<int>(spec.format.size() * 8);
  image.pixels.create(spec.height, spec.width, CV_MAKETYPE(CV_32F, spec.nchannels));
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data)) {
    std::string why = input->geterror();
    ThrowFileError(name, "cannot decode image (truncated or corrupt?)" + (why.empty() ? "" : ": " + why));
  }
  for (const auto& attribute : spec.extra_attribs) {
    if (attribute.type() == OIIO::TypeDesc::STRING) image.text[attribute.name().string()] = attribute.get_string();
  }
  input->close();
  return image;
}

int ReadImageInto(const std::filesystem::path& path, cv::Mat& destination) {
  const std::string name = path.string();
  auto input = OIIO::ImageInput::open(name);
  if (!input) {
    std::string why = OIIO::geterror();
    ThrowFileError(name, why.empty() ? "cannot open image" : why);
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width != destination.cols || spec.height != destination.rows)
    ThrowFileError(name, "image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ", expected " +
                             std::to_string(destination.cols) + "x" + std::to_string(destination.rows) +
                             " like the other views");
  if (spec.nchannels < destination.channels())
    ThrowFileError(name, "image has " + std::to_string(spec.nchannels) + " channels, expected " +
                             std::to_string(destination.channels()));
  if (destination.depth() != CV_32F || !destination.isContinuous())
    throw Error("ReadImageInto: destination must be a continuous float image");
  if (!input->read_image(0, 0, 0, destination.channels(), OIIO::TypeDesc::FLOAT, destination.data)) {
    std::string why = input->geterror();
    ThrowFileError(name, "cannot decode image (truncated or corrupt?)" + (why.empty() ? "" : ": " + why));
  }
  return static_cast<int>(spec.format.size() * 8);
}

void WriteImage(const cv::Mat& image, const std::filesystem::path& path, int bit_depth,
                const std::map<std::string, std::string>& text) {
  const std::string name = path.string();
  if (image.empty()) ThrowFileError(name, "refusing to write an empty image");
  if (!image.isContinuous()) {
    WriteImage(image.clone(), path, bit_depth, text);
    return;
  }
  AtomicOutput output(path);
  auto writer = OIIO::ImageOutput::create(output.temporary().string());
  if (!writer) ThrowFileError(name, "no image writer for this file extension: " + OIIO::geterror());
  OIIO::TypeDesc storage = StorageType(bit_depth);
  if (!writer->supports("channelformats") && storage == OIIO::TypeDesc::FLOAT &&
      std::string(writer->format_name()) == "png")
    storage = OIIO::TypeDesc::UINT16;
  OIIO::ImageSpec spec(image.cols, image.rows, image.channels(), storage);
  for (const auto& [key, value] : text) spec.attribute(key, value);
  if (!writer->open(output.temporary().string(), spec)) ThrowFileError(name, "cannot create: " + writer->geterror());
  if (!writer->write_image(MatType(image.depth()), image.data))
    ThrowFileError(name, "write failed: " + writer->geterror());
  if (!writer->close()) ThrowFileError(name, "write failed: " + writer->geterror());
  output.Commit();
}

}  // namespace lfsp
