#include "lfsp/core/view_crop.h"

#include <algorithm>
#include <string>

#include "lfsp/core/error.h"

namespace lfsp {
namespace {

LightFieldShape CroppedShape(const LightFieldShape& shape, int n) {
  const int available = std::min(shape.nu, shape.nv);
  if (n < 1 || n > available || (available - n) % 2 != 0) {
    throw Error("central views: cannot take " + std::to_string(n) + "x" + std::to_string(n) + " views of " +
                ToString(shape) + " (need 1.." + std::to_string(available) + ", same parity)");
  }
  LightFieldShape cropped = shape;
  cropped.nu = cropped.nv = n;
  return cropped;
}

template <typename T>
void CopyCentralViews(const Array4D<T>& from, Array4D<T>& to) {
  const int n = to.shape().nu;
  const int u0 = (from.shape().nu - n) / 2, v0 = (from.shape().nv - n) / 2;
  const std::size_t samples = from.shape().ViewSamples();
  for (int v = 0; v < n; ++v)
    for (int u = 0; u < n; ++u) {
      const T* source = from.ViewData(ViewIndex{u + u0, v + v0});
      std::copy(source, source + samples, to.ViewData(ViewIndex{u, v}));
    }
}

}  // namespace

LightField CentralViews(const LightField& light_field, int n) {
  LightField out(CroppedShape(light_field.shape(), n));
  CopyCentralViews(light_field, out);
  out.transfer = light_field.transfer;
  out.metadata = light_field.metadata;
  if (light_field.HasWeights()) {
    out.EnableWeights();
    CopyCentralViews(light_field.weights(), out.weights());
  }
  return out;
}

Labels CentralViews(const Labels& labels, int n) {
  Labels out(CroppedShape(labels.shape(), n));
  CopyCentralViews(labels, out);
  return out;
}

}  // namespace lfsp
