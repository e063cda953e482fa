#pragma once

#include <limits>

namespace lfsp::segment {

// std::lround for pixel coordinates, without the library call: glibc's lround is not inlined without SSE4.1 or
// -fno-math-errno, and the metrics' carrying loops spent 2 % of a full Illum pipeline in it. Halves round away
// from zero, as lround does (exactly so for float arguments, which the +-0.5 in double cannot round). Values
// beyond any image (a hostile disparity map's 1e38, NaN) give the smallest int, which every caller's bounds check
// rejects.
inline int RoundHalfAway(double x) {
  if (!(x > -2.0e9 && x < 2.0e9)) return std::numeric_limits<int>::min();
  return static_cast<int>(x < 0.0 ? x - 0.5 : x + 0.5);
}

}  // namespace lfsp::segment
