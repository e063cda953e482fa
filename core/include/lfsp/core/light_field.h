#pragma once

#include <cstddef>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "lfsp/core/conventions.h"
#include "lfsp/core/metadata.h"
#include "lfsp/core/srgb.h"  // the transfer curve; users of Transfer reach SrgbToLinear through this header
#include "lfsp/core/uninitialized_vector.h"

namespace lfsp {

// How sample values relate to scene radiance. Decoders produce linear data; PNG views are usually sRGB.
enum class Transfer { kLinear, kSrgb };

std::string ToString(Transfer transfer);
Transfer TransferFromString(const std::string& name);  // throws lfsp::Error on an unknown name
// The same for a name read from a file: the error names `file` and `where` in it (an attribute, a text chunk).
Transfer TransferFromFile(const std::string& name, const std::string& file, const std::string& where);

// The size of a 4D light field: nv x nu views of height x width pixels with `channels` samples each.
struct LightFieldShape {
  int nu = 0;
  int nv = 0;
  int width = 0;
  int height = 0;
  int channels = 3;

  std::size_t ViewPixels() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  std::size_t ViewSamples() const { return ViewPixels() * static_cast<std::size_t>(channels); }
  std::size_t Views() const { return static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv); }
  std::size_t TotalSamples() const { return Views() * ViewSamples(); }
  ViewIndex Centre() const { return CentreView(nu, nv); }
  bool Contains(ViewIndex view) const { return view.u >= 0 && view.u < nu && view.v >= 0 && view.v < nv; }
  friend bool operator==(const LightFieldShape&, const LightFieldShape&) = default;
};

std::string ToString(const LightFieldShape& shape);  // "9x9 views of 512x512x3"

// A rectangular block of a light field's views: `nu` x `nv` views from view `first` (its top-left view) on.
struct ViewBlock {
  ViewIndex first;
  int nu = 0;
  int nv = 0;
};

// A dense 4D array with memory layout [v][u][y][x][c]: every view is one contiguous row-major image, so View()
// wraps it into a cv::Mat without copying.
template <typename T>
class Array4D {
 public:
  // For arrays the caller writes in full right away (in parallel, say): no fill pass over them first.
  struct Unfilled {};

  Array4D() = default;
  explicit Array4D(const LightFieldShape& shape, T fill = T{}) : shape_(shape), data_(shape.TotalSamples(), fill) {}
  Array4D(const LightFieldShape& shape, Unfilled) : shape_(shape), data_(shape.TotalSamples()) {}

  const LightFieldShape& shape() const { return shape_; }
  bool empty() const { return data_.empty(); }

  T* data() { return data_.data(); }
  const T* data() const { return data_.data(); }
  std::size_t size() const { return data_.size(); }

  T* ViewData(ViewIndex view) { return data_.data() + ViewOffset(view); }
  const T* ViewData(ViewIndex view) const { return data_.data() + ViewOffset(view); }

  // Element access in memory order (view, row, column, channel).
  T& at(ViewIndex view, int y, int x, int c = 0) { return data_[SampleOffset(view, y, x, c)]; }
  const T& at(ViewIndex view, int y, int x, int c = 0) const { return data_[SampleOffset(view, y, x, c)]; }

  std::size_t ViewOffset(ViewIndex view) const {
    return (static_cast<std::size_t>(view.v) * static_cast<std::size_t>(shape_.nu) + static_cast<std::size_t>(view.u)) *
           shape_.ViewSamples();
  }
  std::size_t SampleOffset(ViewIndex view, int y, int x, int c) const {
    return ViewOffset(view) +
           (static_cast<std::size_t>(y) * static_cast<std::size_t>(shape_.width) + static_cast<std::size_t>(x)) *
               static_cast<std::size_t>(shape_.channels) +
           static_cast<std::size_t>(c);
  }

 protected:
  LightFieldShape shape_;
  UninitializedVector<T> data_;
};

// Float samples in [0, 1], RGB order, with optional per-ray weights (vignetting / confidence, one channel).
class LightField : public Array4D<float> {
 public:
  LightField() = default;
  explicit LightField(const LightFieldShape& shape) : Array4D<float>(shape) {}
  // Samples left unset, for a writer that sets every one (no serial pass over the pages before it).
  LightField(const LightFieldShape& shape, Unfilled) : Array4D<float>(shape, Unfilled{}) {}

  // Zero-copy views of the data: the returned cv::Mat shares memory with this light field.
  cv::Mat View(ViewIndex view);
  cv::Mat View(ViewIndex view) const;  // read-only by convention; do not write through it

  Transfer transfer = Transfer::kSrgb;
  Metadata metadata = Metadata::object();

  bool HasWeights() const { return !weights_.empty(); }
  void EnableWeights(float fill = 1.0f);  // allocates one weight per ray
  void EnableWeights(Unfilled);           // the same, left unset for a writer that sets every one
  void DropWeights() { weights_ = {}; }
  Array4D<float>& weights() { return weights_; }
  const Array4D<float>& weights() const { return weights_; }
  cv::Mat WeightView(ViewIndex view);

 private:
  Array4D<float> weights_;
};

// Whether the light field was decoded from a lenslet sensor (the decoder records itself in metadata["decode"]): its
// samples then carry resampled sensor noise, and at most 12 bits of data.
inline bool DecodedFromSensor(const LightField& light_field) { return light_field.metadata.contains("decode"); }

// Label per ray (int32, same layout, one channel); -1 = unlabelled.
class Labels : public Array4D<std::int32_t> {
 public:
  static constexpr std::int32_t kUnlabelled = -1;
  Labels() = default;
  // `shape.channels` is ignored: labels always have one channel.
  explicit Labels(LightFieldShape shape, std::int32_t fill = kUnlabelled);
  Labels(LightFieldShape shape, Unfilled);
  cv::Mat View(ViewIndex view);
  cv::Mat View(ViewIndex view) const;
};

// Throws lfsp::Error naming `where` when a label is below Labels::kUnlabelled (files may hold any integer; the
// stages index by label, so only -1 and 0.. are meaningful).
void RequireValidLabelValues(const Labels& labels, const std::string& where);

// Throws lfsp::Error naming `what` unless `labels` has the light field's views and view size.
void RequireLabelsMatch(const Labels& labels, const LightFieldShape& shape, const std::string& what);

// The same segmentation with labels renumbered 0..n-1 in order of first appearance (kUnlabelled stays): scoring
// allocates per label, so a file's sparse label values (5,000,000 in a 400 KB bundle) must not size its tables.
Labels DenselyRelabelled(const Labels& labels);

// Centre-view disparity, float32 height x width, pixels per view step (docs/DESIGN.md convention).
class DisparityMap {
 public:
  DisparityMap() = default;
  DisparityMap(int width, int height, float fill = 0.0f);

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return values_.empty(); }
  float& at(int y, int x) { return values_[Index(y, x)]; }
  float at(int y, int x) const { return values_[Index(y, x)]; }
  float* data() { return values_.data(); }
  const float* data() const { return values_.data(); }
  cv::Mat Mat();        // zero-copy CV_32FC1
  cv::Mat Mat() const;  // read-only by convention

 private:
  std::size_t Index(int y, int x) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }
  int width_ = 0;
  int height_ = 0;
  std::vector<float> values_;
};

}  // namespace lfsp
