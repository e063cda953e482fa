#include "lfsp/core/view_crop.h"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "lfsp/core/error.h"

namespace lfsp {

LightFieldShape CentralShape(const LightFieldShape& shape, int n) {
  const int available = std::min(shape.nu, shape.nv);
  if (n < 1 || n > available || (available - n) % 2 != 0) {
    throw Error("central views: cannot take " + std::to_string(n) + "x" + std::to_string(n) + " views of " +
                ToString(shape) + " (need 1.." + std::to_string(available) + ", same parity)");
  }
  LightFieldShape cropped = shape;
  cropped.nu = cropped.nv = n;
  return cropped;
}

namespace {

template <typename T>
void CopyCentralViews(const Array4D<T>& from, Array4D<T>& to) {
  const int n = to.shape().nu;
  const ViewIndex first = CentralViewBlock(from.shape(), n).first;
  const std::size_t samples = from.shape().ViewSamples();
  for (int v = 0; v < n; ++v)
    for (int u = 0; u < n; ++u) {
      const T* source = from.ViewData(ViewIndex{u + first.u, v + first.v});
      std::copy(source, source + samples, to.ViewData(ViewIndex{u, v}));
    }
}

}  // namespace

ViewBlock CentralViewBlock(const LightFieldShape& shape, int n) {
  CentralShape(shape, n);  // throws with the reason if it cannot be taken
  return {{(shape.nu - n) / 2, (shape.nv - n) / 2}, n, n};
}

LightField CentralViews(const LightField& light_field, int n) {
  LightField out(CentralShape(light_field.shape(), n));
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
  Labels out(CentralShape(labels.shape(), n));
  CopyCentralViews(labels, out);
  return out;
}

double MeanOfWeights(const float* weights, std::size_t count) {
  double sum = 0.0;
  for (std::size_t i = 0; i < count; ++i) sum += weights[i];
  return sum / static_cast<double>(count);
}

double MeanViewWeight(const LightField& light_field, ViewIndex view) {
  return MeanOfWeights(light_field.weights().ViewData(view), light_field.shape().ViewPixels());
}

namespace {

// The lowest mean weight over the views at Chebyshev distance `from` .. `to` from the centre.
double LeastWeight(const LightFieldShape& shape, const std::function<double(ViewIndex)>& mean_weight, int from,
                   int to) {
  const ViewIndex centre = shape.Centre();
  double least = 1.0;
  for (int v = centre.v - to; v <= centre.v + to; ++v)
    for (int u = centre.u - to; u <= centre.u + to; ++u)
      if (std::max(std::abs(u - centre.u), std::abs(v - centre.v)) >= from)
        least = std::min(least, mean_weight(ViewIndex{u, v}));
  return least;
}

}  // namespace

int WellLitCentralSize(const LightFieldShape& shape, const std::function<double(ViewIndex)>& mean_weight,
                       double threshold) {
  const int available = std::min(shape.nu, shape.nv);
  int n = available % 2 == 1 ? 1 : 2;
  while (n + 2 <= available) {
    const int ring = (n + 1) / 2;
    if (LeastWeight(shape, mean_weight, ring, ring) < threshold) break;
    n += 2;
  }
  return n;
}

ViewChoice ChooseViews(const LightField& light_field, int requested) {
  std::function<double(ViewIndex)> mean_weight;
  if (light_field.HasWeights())
    mean_weight = [&light_field](ViewIndex view) { return MeanViewWeight(light_field, view); };
  return ChooseViews(light_field.shape(), mean_weight, requested);
}

ViewChoice ChooseViews(const LightFieldShape& shape, const std::function<double(ViewIndex)>& mean_weight,
                       int requested) {
  ViewChoice choice;
  choice.available = std::min(shape.nu, shape.nv);
  if (requested > 0) {
    CentralShape(shape, requested);  // throws with the reason if it cannot be taken
    choice.n = requested;
    choice.reason = OptionName("views") + " " + std::to_string(requested);
  } else if (!mean_weight) {
    choice.n = choice.available;
    choice.reason = "all views (the light field has no weights)";
  } else {
    choice.n = WellLitCentralSize(shape, mean_weight);
    choice.reason = "central " + std::to_string(choice.n) + "x" + std::to_string(choice.n) + " of " +
                    std::to_string(choice.available) + "x" + std::to_string(choice.available) +
                    ": every view's mean weight >= " + std::to_string(kWellLitWeight).substr(0, 3) + " (" +
                    OptionName("views") + " to override)";
  }
  if (mean_weight) choice.least_weight = LeastWeight(shape, mean_weight, 0, (choice.n - 1) / 2);
  return choice;
}

int ViewsForLabels(int requested, const LightFieldShape& light_field, const LightFieldShape& labels) {
  if (requested > 0) return requested;
  return labels.nu < light_field.nu ? labels.nu : 0;
}

void KeepCentralViews(LightField& light_field, std::optional<Labels>& labels, int n) {
  if (n != light_field.shape().nu || n != light_field.shape().nv) light_field = CentralViews(light_field, n);
  if (labels && (n != labels->shape().nu || n != labels->shape().nv)) labels = CentralViews(*labels, n);
}

ViewChoice KeepChosenViews(LightField& light_field, std::optional<Labels>& labels, int requested) {
  ViewChoice choice = ChooseViews(light_field, requested);
  KeepCentralViews(light_field, labels, choice.n);
  return choice;
}

}  // namespace lfsp
