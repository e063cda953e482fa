#include "lfsp/core/image_io.h"

#include <OpenImageIO/imageio.h>

#include <zlib.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <vector>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/file_names.h"
#include "lfsp/core/input_limits.h"
#include "lfsp/core/sample_levels.h"

namespace lfsp {
namespace {

// zlib level of every PNG written. OpenImageIO's default is 6; level 1 wrote the pipeline's focal stack of a full
// Illum capture (five 622x432 slices) in 0.31-0.36 s instead of 0.51-0.55 s, with files 18 % larger and the same
// pixels (BENCHMARKS.md, thirty-sixth session). OpenCV's PNG encoder, which the report uses, defaults to 1 as well.
constexpr int kPngCompressionLevel = 1;

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

// Reads all pixels of the open file into `destination` (CV_32FC(n)). Integer files are read in their own type and
// scaled here as k / (2^bits - 1), so every 8- or 16-bit value maps to exactly the same float on every path.
bool ReadSamples(OIIO::ImageInput& input, cv::Mat& destination) {
  const OIIO::ImageSpec& spec = input.spec();
  const int channels = destination.channels();
  const std::size_t count = destination.total() * static_cast<std::size_t>(channels);
  float* out = destination.ptr<float>();
  if (spec.format == OIIO::TypeDesc::UINT8) {
    std::vector<std::uint8_t> raw(count);
    if (!input.read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, raw.data())) return false;
    for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<float>(raw[i]) / 255.0f;
    return true;
  }
  if (spec.format == OIIO::TypeDesc::UINT16) {
    std::vector<std::uint16_t> raw(count);
    if (!input.read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT16, raw.data())) return false;
    for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<float>(raw[i]) / 65535.0f;
    return true;
  }
  return input.read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, out);
}

// Whether libjpeg's remarks say the compressed data is damaged, not merely unusual (a header remark such as an
// unknown JFIF revision is not).
bool ReportsJpegDamage(const std::string& remarks) {
  return remarks.find("Premature end of JPEG file") != std::string::npos ||
         remarks.find("Corrupt JPEG data") != std::string::npos;
}

// ReadSamples, failing also when the read met damage that the format's library only warns about. libjpeg decodes a
// truncated or corrupt JPEG to the end, filling what is missing with grey ("Premature end of JPEG file"), and
// libtiff's strip reader may come short of a cut TIFF's last strips: OpenImageIO records these as errors of the
// input but reports the read as done. A progressive JPEG is decoded whole while it is opened, so its damage is among
// what the input recorded then; the rest of that (header remarks) is dropped. A JPEG cut after its last scanline,
// whose end-of-image marker alone is missing, is refused too: libjpeg says the same of it. `why`: the reader's
// message when it fails.
bool ReadAsFloat(OIIO::ImageInput& input, cv::Mat& destination, std::string& why) {
  const std::string at_open = input.geterror();
  if (ReportsJpegDamage(at_open)) {
    why = at_open;
    return false;
  }
  if (ReadSamples(input, destination) && !input.has_error()) return true;
  why = input.geterror();
  return false;
}

// Float samples in [0, 1] quantised with rounding to the storage type (OpenImageIO's own conversion may truncate).
cv::Mat QuantisedForStorage(const cv::Mat& image, OIIO::TypeDesc storage) {
  if (image.depth() != CV_32F || (storage != OIIO::TypeDesc::UINT8 && storage != OIIO::TypeDesc::UINT16)) return image;
  const bool eight = storage == OIIO::TypeDesc::UINT8;
  const float scale = eight ? 255.0f : 65535.0f;
  cv::Mat quantised(image.rows, image.cols, CV_MAKETYPE(eight ? CV_8U : CV_16U, image.channels()));
  const std::size_t count = image.total() * static_cast<std::size_t>(image.channels());
  const float* in = image.ptr<float>();
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t level = SampleLevel(in[i], scale);
    if (eight) {
      quantised.ptr<std::uint8_t>()[i] = static_cast<std::uint8_t>(level);
    } else {
      quantised.ptr<std::uint16_t>()[i] = static_cast<std::uint16_t>(level);
    }
  }
  return quantised;
}

// libpng reports a truncated file or a corrupt chunk on stderr by itself before OpenImageIO sees the error, which
// would break the CLI's one-line error contract. Walking the chunks first (their lengths against the file, their
// CRCs) catches both cleanly, at the cost of one extra read of the file.
void CheckPngIsComplete(const std::filesystem::path& path) {
  if (LowerExtension(path) != ".png") return;
  const std::string name = path.string();
  std::FILE* file = std::fopen(name.c_str(), "rb");
  if (file == nullptr) ThrowFileError(name, "cannot open");
  std::error_code ec;
  const auto size = static_cast<long long>(std::filesystem::file_size(path, ec));
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  unsigned char header[8];
  std::string problem;
  if (std::fread(header, 1, 8, file) != 8 || std::memcmp(header, kSignature, 8) != 0) {
    problem = "not a PNG file (bad signature)";
  } else {
    long long offset = 8;
    while (problem.empty()) {
      if (std::fread(header, 1, 8, file) != 8) {
        problem = "truncated PNG: file ends at byte " + std::to_string(offset) + " before the IEND chunk";
        break;
      }
      const long long length =
          (static_cast<long long>(header[0]) << 24) | (header[1] << 16) | (header[2] << 8) | header[3];
      const std::string type(reinterpret_cast<const char*>(header + 4), 4);
      const long long next = offset + 8 + length + 4;  // header, data, CRC
      if (next > size) {
        problem = "truncated PNG: chunk " + type + " at byte " + std::to_string(offset) + " runs past the end (" +
                  std::to_string(size) + " bytes)";
        break;
      }
      // libpng also prints its own line for a bad CRC: check every chunk's CRC here (zlib's crc32, ~1 GB/s).
      std::vector<unsigned char> body(static_cast<std::size_t>(length) + 4);
      std::memcpy(body.data(), header + 4, 4);
      unsigned char stored[4];
      if (std::fread(body.data() + 4, 1, static_cast<std::size_t>(length), file) != static_cast<std::size_t>(length) ||
          std::fread(stored, 1, 4, file) != 4) {
        problem = "cannot read PNG chunk " + type + " at byte " + std::to_string(offset);
        break;
      }
      const auto crc = static_cast<std::uint32_t>(crc32(0L, body.data(), static_cast<uInt>(body.size())));
      const std::uint32_t expected = (static_cast<std::uint32_t>(stored[0]) << 24) |
                                     (static_cast<std::uint32_t>(stored[1]) << 16) |
                                     (static_cast<std::uint32_t>(stored[2]) << 8) | stored[3];
      if (crc != expected) {
        problem = "corrupt PNG: chunk " + type + " at byte " + std::to_string(offset) + " fails its CRC check";
        break;
      }
      if (type == "IEND") break;
      offset = next;
    }
  }
  std::fclose(file);
  if (!problem.empty()) ThrowFileError(name, problem);
}

// Opens an image for reading after the checks every reader needs: complete PNG chunks, a layout lfsp handles.
std::unique_ptr<OIIO::ImageInput> OpenChecked(const std::filesystem::path& path,
                                              ImageAlpha alpha = ImageAlpha::kAssociated) {
  const std::string name = path.string();
  RequireRegularFile(path);
  CheckPngIsComplete(path);
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // the readers leave colour as stored
  auto input = OIIO::ImageInput::open(name, alpha == ImageAlpha::kAsStored ? &config : nullptr);
  if (!input) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "cannot open image";
    ThrowFileError(name, why);
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.nchannels > 4)
    ThrowFileError(name, "unsupported image layout " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                             "x" + std::to_string(spec.nchannels));
  return input;
}

}  // namespace

ImageHeader ReadImageHeader(const std::filesystem::path& path) {
  const auto input = OpenChecked(path);
  const OIIO::ImageSpec& spec = input->spec();
  return {spec.width, spec.height, spec.nchannels, static_cast<int>(spec.format.size() * 8)};
}

ImageFile ReadImage(const std::filesystem::path& path, ImageAlpha alpha) {
  const std::string name = path.string();
  auto input = OpenChecked(path, alpha);
  const OIIO::ImageSpec& spec = input->spec();
  CheckDeclaredAllocation(
      name,
      SaturatingBytes({static_cast<std::uint64_t>(spec.width), static_cast<std::uint64_t>(spec.height),
                       static_cast<std::uint64_t>(spec.nchannels)},
                      sizeof(float)),
      FileBytes(path));
  ImageFile image;
  image.bit_depth = static_cast<int>(spec.format.size() * 8);
  image.pixels.create(spec.height, spec.width, CV_MAKETYPE(CV_32F, spec.nchannels));
  if (std::string why; !ReadAsFloat(*input, image.pixels, why)) {
    ThrowFileError(name, "cannot decode image (truncated or corrupt?)" + (why.empty() ? "" : ": " + why));
  }
  for (const auto& attribute : spec.extra_attribs) {
    if (attribute.type() == OIIO::TypeDesc::STRING) image.text[attribute.name().string()] = attribute.get_string();
  }
  image.orientation = spec.get_int_attribute("Orientation", 1);
  input->close();
  return image;
}

int ReadImageInto(const std::filesystem::path& path, cv::Mat& destination) {
  const std::string name = path.string();
  auto input = OpenChecked(path);
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
  if (std::string why; !ReadAsFloat(*input, destination, why)) {
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
  spec.attribute("png:compressionLevel", kPngCompressionLevel);  // read by the PNG writer only
  if (!writer->open(output.temporary().string(), spec)) ThrowFileError(name, "cannot create: " + writer->geterror());
  const cv::Mat pixels = QuantisedForStorage(image, storage);
  if (!writer->write_image(MatType(pixels.depth()), pixels.data))
    ThrowFileError(name, "write failed: " + writer->geterror());
  if (!writer->close()) ThrowFileError(name, "write failed: " + writer->geterror());
  output.Commit();
}

void WriteAnimation(const std::vector<cv::Mat>& frames, const std::filesystem::path& path, double frames_per_second) {
  const std::string name = path.string();
  if (frames.empty()) ThrowFileError(name, "refusing to write an animation without frames");
  for (const cv::Mat& frame : frames)
    if (frame.type() != CV_8UC3 || frame.size() != frames.front().size())
      throw Error("WriteAnimation: frames must be 8-bit RGB of one size");
  const std::string extension = LowerExtension(path);
  AtomicOutput output(path);
  if (extension == ".gif") {
    auto writer = OIIO::ImageOutput::create("gif");
    if (!writer) ThrowFileError(name, "no GIF writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(frames.front().cols, frames.front().rows, 3, OIIO::TypeDesc::UINT8);
    const int rate[2] = {static_cast<int>(std::lround(frames_per_second * 100)), 100};
    spec.attribute("FramesPerSecond", OIIO::TypeRational, rate);
    spec.attribute("gif:LoopCount", 0);
    std::vector<OIIO::ImageSpec> specs(frames.size(), spec);
    if (!writer->open(output.temporary().string(), static_cast<int>(specs.size()), specs.data()))
      ThrowFileError(name, "cannot create: " + writer->geterror());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (i > 0 && !writer->open(output.temporary().string(), spec, OIIO::ImageOutput::AppendSubimage))
        ThrowFileError(name, "cannot add frame " + std::to_string(i) + ": " + writer->geterror());
      cv::Mat contiguous = frames[i].isContinuous() ? frames[i] : frames[i].clone();
      if (!writer->write_image(OIIO::TypeDesc::UINT8, contiguous.data))
        ThrowFileError(name, "write failed: " + writer->geterror());
    }
    if (!writer->close()) ThrowFileError(name, "write failed: " + writer->geterror());
  } else if (extension == ".mp4") {
    cv::VideoWriter video(output.temporary().string() + ".mp4", cv::CAP_FFMPEG,
                          cv::VideoWriter::fourcc('m', 'p', '4', 'v'), frames_per_second, frames.front().size());
    if (!video.isOpened()) ThrowFileError(name, "cannot create an MP4 (OpenCV's FFmpeg writer is not available)");
    cv::Mat bgr;
    for (const cv::Mat& frame : frames) {
      cv::cvtColor(frame, bgr, cv::COLOR_RGB2BGR);
      video.write(bgr);
    }
    video.release();
    std::filesystem::rename(output.temporary().string() + ".mp4", output.temporary());
  } else {
    ThrowFileError(name, "unknown animation format (expected .gif or .mp4)");
  }
  output.Commit();
}

}  // namespace lfsp
