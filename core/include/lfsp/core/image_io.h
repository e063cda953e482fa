#pragma once

#include <filesystem>
#include <map>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace lfsp {

// Every image file goes through OpenImageIO (PNG, TIFF, EXR, JPEG, ...).

struct ImageFile {
  cv::Mat pixels;                           // CV_32FC(n): integer files scaled to [0, 1], float files as stored
  int bit_depth = 8;                        // bits per sample on disk (8, 16, 32 for float)
  std::map<std::string, std::string> text;  // string attributes (PNG text chunks, e.g. "lfsp:nu")
  int orientation = 1;                      // Exif/TIFF Orientation (1: as stored); the pixels are left as stored
};

// The colour samples of a file whose alpha is unassociated (PNG's, most TIFFs'): kAssociated multiplies them by alpha,
// as OpenImageIO does by default; kAsStored keeps the colour the file holds, for readers that ignore alpha.
enum class ImageAlpha { kAssociated, kAsStored };

// Reads the whole image. Its declared size is checked against the file's (lfsp/core/input_limits.h) first. A
// truncated or corrupt file is lfsp::Error naming it, also when the format's library only warns (a JPEG cut short).
ImageFile ReadImage(const std::filesystem::path& path, ImageAlpha alpha = ImageAlpha::kAssociated);

// What an image file declares, read from its header without decoding the pixels (a few small reads).
struct ImageHeader {
  int width = 0;
  int height = 0;
  int channels = 0;
  int bit_depth = 8;
};
ImageHeader ReadImageHeader(const std::filesystem::path& path);

// An animation of 8-bit RGB frames, by extension: `.gif` (OpenImageIO, looping) or `.mp4` (OpenCV's FFmpeg
// writer, MPEG-4 part 2). Written under a temporary name and renamed when complete.
void WriteAnimation(const std::vector<cv::Mat>& frames, const std::filesystem::path& path, double frames_per_second);

// Reads an image straight into `destination` (pre-allocated CV_32FC(n), continuous), without an intermediate copy.
// The file must have exactly destination's width and height and at least n channels (extra channels, such as
// alpha, are dropped). Returns the file's bits per sample.
int ReadImageInto(const std::filesystem::path& path, cv::Mat& destination);

// Writes `image` (CV_32F in [0, 1], quantised with rounding; or CV_8U / CV_16U as is; 1, 3 or 4 channels) with
// `bit_depth` bits per sample (8 or 16; float formats such as EXR keep float), through a temporary file.
void WriteImage(const cv::Mat& image, const std::filesystem::path& path, int bit_depth = 8,
                const std::map<std::string, std::string>& text = {});

}  // namespace lfsp
