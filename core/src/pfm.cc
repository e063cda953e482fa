#include "lfsp/core/pfm.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <sstream>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/input_limits.h"

namespace lfsp {
namespace {

constexpr int kMaxDimension = 1 << 16;

// Reads one whitespace-delimited header token starting at `pos`; leaves `pos` on the delimiter after it.
std::string NextToken(const std::string& bytes, std::size_t& pos, std::size_t limit) {
  while (pos < limit && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
  const std::size_t begin = pos;
  while (pos < limit && !std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
  return bytes.substr(begin, pos - begin);
}

int ParseDimension(const std::string& token, const std::string& path, const char* what) {
  if (token.empty() || token.size() > 6 || token.find_first_not_of("0123456789") != std::string::npos)
    ThrowFileError(path, std::string("bad PFM header: ") + what + " '" + token + "' is not a positive integer");
  const int value = std::stoi(token);
  if (value <= 0 || value > kMaxDimension)
    ThrowFileError(path, std::string("bad PFM header: ") + what + " " + token + " out of range");
  return value;
}

float ByteSwapped(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  bits = ((bits & 0xFFu) << 24) | ((bits & 0xFF00u) << 8) | ((bits >> 8) & 0xFF00u) | (bits >> 24);
  std::memcpy(&value, &bits, sizeof bits);
  return value;
}

}  // namespace

DisparityMap ReadPfm(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::string bytes = ReadWholeFile(path);
  const std::size_t header_limit = std::min<std::size_t>(bytes.size(), 256);
  std::size_t pos = 0;
  const std::string magic = NextToken(bytes, pos, header_limit);
  if (magic == "PF") ThrowFileError(name, "PFM has three channels (PF); a disparity map needs one (Pf)");
  if (magic != "Pf") ThrowFileError(name, "not a PFM file (magic '" + magic.substr(0, 8) + "', expected 'Pf')");
  const int width = ParseDimension(NextToken(bytes, pos, header_limit), name, "width");
  const int height = ParseDimension(NextToken(bytes, pos, header_limit), name, "height");
  const std::string scale_token = NextToken(bytes, pos, header_limit);
  double scale = 0.0;
  try {
    std::size_t used = 0;
    scale = std::stod(scale_token, &used);
    if (used != scale_token.size()) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    ThrowFileError(name, "bad PFM header: scale '" + scale_token + "' is not a number");
  }
  if (scale == 0.0 || !std::isfinite(scale)) ThrowFileError(name, "bad PFM header: scale must be non-zero");
  if (pos >= bytes.size()) ThrowFileError(name, "truncated PFM: header ends without data");
  ++pos;  // exactly one whitespace byte separates the header from the data

  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const std::size_t expected = pixels * sizeof(float);
  if (bytes.size() - pos < expected)
    ThrowFileError(name, "truncated PFM: expected " + std::to_string(expected) + " data bytes for " +
                             std::to_string(width) + "x" + std::to_string(height) + ", found " +
                             std::to_string(bytes.size() - pos));

  const bool file_little_endian = scale < 0.0;
  const bool swap = file_little_endian != (std::endian::native == std::endian::little);
  DisparityMap map(width, height);
  // PFM stores the bottom image row first.
  for (int file_row = 0; file_row < height; ++file_row) {
    const int image_row = height - 1 - file_row;
    float* destination = map.data() + static_cast<std::size_t>(image_row) * width;
    std::memcpy(destination, bytes.data() + pos + static_cast<std::size_t>(file_row) * width * sizeof(float),
                static_cast<std::size_t>(width) * sizeof(float));
    if (swap)
      for (int x = 0; x < width; ++x) destination[x] = ByteSwapped(destination[x]);
  }
  return map;
}

void WritePfm(const DisparityMap& disparity, const std::filesystem::path& path) {
  if (disparity.empty()) throw Error(FileMessage(path.string(), "refusing to write an empty disparity map"));
  AtomicOutput output(path);
  {
    std::ofstream file(output.temporary(), std::ios::binary);
    if (!file) ThrowFileError(path.string(), "cannot create");
    const double scale = std::endian::native == std::endian::little ? -1.0 : 1.0;
    file << "Pf\n" << disparity.width() << " " << disparity.height() << "\n" << (scale < 0 ? "-1.0" : "1.0") << "\n";
    for (int image_row = disparity.height() - 1; image_row >= 0; --image_row) {
      file.write(
          reinterpret_cast<const char*>(disparity.data() + static_cast<std::size_t>(image_row) * disparity.width()),
          static_cast<std::streamsize>(disparity.width() * sizeof(float)));
    }
    if (!file.flush()) ThrowFileError(path.string(), "write failed");
  }
  output.Commit();
}

void WriteDisparityPng16(const DisparityMap& disparity, const std::filesystem::path& path) {
  float low = std::numeric_limits<float>::infinity(), high = -low;
  const std::size_t count = static_cast<std::size_t>(disparity.width()) * static_cast<std::size_t>(disparity.height());
  for (std::size_t i = 0; i < count; ++i)
    if (std::isfinite(disparity.data()[i])) {
      low = std::min(low, disparity.data()[i]);
      high = std::max(high, disparity.data()[i]);
    }
  if (!(high >= low)) ThrowFileError(path.string(), "the disparity map has no finite value to write");
  const double span = high > low ? high - low : 1.0;
  cv::Mat encoded(disparity.height(), disparity.width(), CV_32FC1);
  for (int y = 0; y < disparity.height(); ++y)
    for (int x = 0; x < disparity.width(); ++x) {
      const float d = disparity.at(y, x);
      const double value = std::isfinite(d) ? 1.0 + std::round((d - low) / span * 65534.0) : 0.0;
      encoded.at<float>(y, x) = static_cast<float>(value / 65535.0);
    }
  char low_text[32], high_text[32];
  std::snprintf(low_text, sizeof low_text, "%.9g", static_cast<double>(low));
  std::snprintf(high_text, sizeof high_text, "%.9g", static_cast<double>(high));
  WriteImage(encoded, path, 16,
             {{"lfsp:disparity_min", low_text},
              {"lfsp:disparity_max", high_text},
              {"lfsp:encoding", "d = min + (value - 1) / 65534 * (max - min); value 0 = no disparity"}});
}

}  // namespace lfsp
