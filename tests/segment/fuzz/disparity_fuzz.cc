// Fuzz target: a disparity map (PFM) given to LFSP as `lfsp segment --disparity` gives it, on a small synthetic 3x3
// light field of the map's size. The map's values reach SLIC's features, the plane fits, the warps and the
// refinement: a map of 3e38 everywhere corrupted the heap inside OpenCV's SLIC (issue 45). The seeds hold the value
// ranges that matter (the largest floats, infinities, NaN, denormals, huge steps); only lfsp::Error may escape.

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "../../core/fuzz/fuzz_file.h"
#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/core/light_field.h"
#include "lfsp/core/pfm.h"
#include "lfsp/segment/lfsp.h"

namespace {

constexpr int kLargestSide = 48;  // keeps one run to milliseconds

lfsp::LightField PatternedLightField(int width, int height) {
  lfsp::LightField light_field({3, 3, width, height, 3});
  for (std::size_t i = 0; i < light_field.size(); ++i)
    light_field.data()[i] = static_cast<float>((i * 37) % 251) / 251.0f;
  return light_field;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const lfsp::DisparityMap disparity = lfsp::ReadPfm(FuzzInputFile(data, size, ".pfm"));
    if (disparity.width() > kLargestSide || disparity.height() > kLargestSide) return 0;
    lfsp::segment::LfspParams params;
    params.size = std::max(2, std::min(disparity.width(), disparity.height()) / 2);
    params.iterations = 2;
    params.slic_iterations = 3;
    params.threads = 1;
    (void)lfsp::segment::SegmentLightField(PatternedLightField(disparity.width(), disparity.height()), disparity,
                                           params);
  } catch (const lfsp::Error&) {
  }
  return 0;
}
