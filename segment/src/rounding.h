#pragma once

#include <limits>

namespace lfsp::segment {

// std::lround for pixel coordinates and disparities, without the library call: glibc's lround is not inlined
// without SSE4.1 or -fno-math-errno, and the metrics' carrying loops spent 2 % of a full Illum pipeline in it.
// Halves round away from zero, as lround does, for every double: the fraction left after truncation is exact, so
// it is compared with 0.5 itself (adding 0.5 first would round 0.49999999999999994 up). Values beyond any image (a
// hostile disparity map's 1e38, NaN) give the smallest int, which every caller's bounds check rejects.
inline int RoundHalfAway(double x) {
  if (!(x > -2.0e9 && x < 2.0e9)) return std::numeric_limits<int>::min();
  int whole = static_cast<int>(x);
  const double fraction = x - whole;
  if (fraction >= 0.5) ++whole;
  if (fraction <= -0.5) --whole;
  return whole;
}

}  // namespace lfsp::segment
