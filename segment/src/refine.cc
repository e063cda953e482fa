#include "refine.h"

#include "lfsp/core/progress.h"
#include "lfsp/core/rounding.h"
#include "lfsp/core/stopwatch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <opencv2/core/mat.hpp>
#include "label_block.h"
#include "planes.h"

namespace lfsp::segment {
namespace {

// Running sums of one 2D slice (label k in one view): mean colour and centroid follow label moves incrementally.
struct Slice {
  double l = 0, a = 0, b = 0, x = 0, y = 0;
  double inv_n = 0;  // 1 / n, kept beside n: every cost evaluation needs it and moves are 20 times rarer
  int n = 0;
};

// The view a sweep is in, with its neighbouring views in the angular clique (b outer, a inner; at most 8).
struct SweptView {
  struct Neighbour {
    const std::int32_t* labels;
    std::uint8_t* flags;  // its rays' awake flags
    int a, b;             // view offset
  };
  int cam = 0, u = 0, v = 0;
  int du = 0, dv = 0;  // offset from the centre view
  bool centre = false;
  std::int32_t* labels = nullptr;
  std::uint8_t* flags = nullptr;
  std::array<Neighbour, 8> neighbours{};
  int neighbour_count = 0;
};

// The shared state of one refinement, with views addressed by camera number.
class Refiner {
 public:
  Refiner(const RefineInputs& inputs, const LfspParams& params, Labels& labels, std::vector<Plane>& planes)
      : in_(inputs),
        p_(params),
        shape_(labels.shape()),
        labels_(labels),
        planes_(planes),
        width_(shape_.width),
        height_(shape_.height),
        view_pixels_(shape_.ViewPixels()),
        centre_(shape_.Centre()),
        slices_(shape_.Views() * static_cast<std::size_t>(inputs.superpixels)),
        active_(shape_.Views() * view_pixels_, 1) {
    inv_colour_ = 1.0 / (p_.colour_scale * p_.colour_scale);
    inv_size_ = 1.0 / (static_cast<double>(p_.size) * p_.size);
    inv_range_ = 1.0 / in_.disparity_range;
    boundary_weight_ = p_.lambda_b / 8.0;
    InitialiseSlices();
  }

  // A phase's views are swept a band of rows at a time, all of them before the next band. A ray's clique reads
  // the same rows of its 8 neighbouring views, which up to 4 views of the phase share: swept band by band, those rows
  // are read from memory once and then from cache, where view by view they were read again for each view, long after
  // they had been evicted (antinous: sweeps 1.31 -> 1.18 s, BENCHMARKS.md, twenty-sixth session). The views of a
  // phase do not read what the others write, so the labels are the same as view by view, bit for bit.
  static constexpr int kBandRows = 16;

  // One pass of label moves over the active boundary rays of every view; returns the number of moves.
  long long Sweep() {
    SnapshotCentroids();
    long long moves = 0;
    for (int phase = 0; phase < 4; ++phase) {
      std::vector<int> cams;
      for (int v = 0; v < shape_.nv; ++v) {
        for (int u = 0; u < shape_.nu; ++u) {
          if ((u % 2) + 2 * (v % 2) == phase) cams.push_back(v * shape_.nu + u);
        }
      }
      const int count = static_cast<int>(cams.size());
      for (int top = 0; top < height_; top += kBandRows) {
        const int bottom = std::min(height_, top + kBandRows);
#pragma omp parallel for schedule(dynamic) reduction(+ : moves)
        for (int i = 0; i < count; ++i) moves += SweepView(cams[static_cast<std::size_t>(i)], top, bottom);
      }
    }
    return moves;
  }

  cv::Mat CentreLabels() { return labels_.View(centre_); }

 private:
  std::int32_t* ViewLabels(int cam) { return labels_.data() + static_cast<std::size_t>(cam) * view_pixels_; }
  const std::int32_t* ViewLabels(int cam) const {
    return labels_.data() + static_cast<std::size_t>(cam) * view_pixels_;
  }
  std::uint8_t* ViewFlags(int cam) { return active_.data() + static_cast<std::size_t>(cam) * view_pixels_; }
  Slice& SliceOf(int cam, int k) {
    return slices_[static_cast<std::size_t>(cam) * static_cast<std::size_t>(in_.superpixels) +
                   static_cast<std::size_t>(k)];
  }
  const Slice& SliceOf(int cam, int k) const {
    return slices_[static_cast<std::size_t>(cam) * static_cast<std::size_t>(in_.superpixels) +
                   static_cast<std::size_t>(k)];
  }
  const float* LabOf(int cam, std::size_t index) const {
    return in_.lab + (static_cast<std::size_t>(cam) * view_pixels_ + index) * 3;
  }

  void InitialiseSlices() {
    const int views = static_cast<int>(shape_.Views());
#pragma omp parallel for schedule(dynamic)
    for (int cam = 0; cam < views; ++cam) {
      const std::int32_t* labels = ViewLabels(cam);
      for (int y = 0; y < height_; ++y) {
        for (int x = 0; x < width_; ++x) {
          const std::size_t index =
              static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
          Add(SliceOf(cam, labels[index]), LabOf(cam, index), x, y, 1);
        }
      }
    }
  }

  // Centre-view centroids and their plane disparities, frozen for one sweep (the centre view changes during it).
  void SnapshotCentroids() {
    const int cam = CameraNumber(centre_, shape_.nu);
    const std::size_t count = static_cast<std::size_t>(in_.superpixels);
    centre_x_.assign(count, 0.0);
    centre_y_.assign(count, 0.0);
    centre_d_.assign(count, 0.0);
    for (std::size_t k = 0; k < count; ++k) {
      const Slice& s = SliceOf(cam, static_cast<int>(k));
      if (s.n <= 0) continue;
      centre_x_[k] = s.x / s.n;
      centre_y_[k] = s.y / s.n;
      centre_d_[k] = planes_[k].AtCentre(centre_x_[k], centre_y_[k]);
    }
  }

  static void Add(Slice& s, const float* lab, int x, int y, int sign) {
    s.l += sign * lab[0];
    s.a += sign * lab[1];
    s.b += sign * lab[2];
    s.x += sign * x;
    s.y += sign * y;
    s.n += sign;
    s.inv_n = s.n > 0 ? 1.0 / s.n : 0.0;
  }

  // Rounded disparity of the ray (x, y) of view offset (du, dv) if it belongs to label k (Eq. 2).
  int RoundedDisparity(int k, int x, int y, int du, int dv) const {
    return RoundHalfAway(RayDisparity(k, x, y, du, dv));
  }
  // A shift beyond the view's size puts every angular neighbour outside it, so the disparity is clamped there: a
  // hostile disparity map's planes (1e30, NaN) would otherwise overflow the integer positions the boundary term and
  // Wake compute from it.
  double RayDisparity(int k, int x, int y, int du, int dv) const {
    const Plane& plane = planes_[static_cast<std::size_t>(k)];
    const double denominator = 1.0 - plane.a * du - plane.b * dv;
    const double numerator = plane.a * x + plane.b * y + plane.c;
    const double d = std::abs(denominator) > 0.1 ? numerator / denominator : numerator;
    const double max_shift = width_ + height_;
    if (std::abs(d) <= max_shift) return d;
    return std::isnan(d) ? 0.0 : std::copysign(max_shift, d);
  }

  // Would removing the ray at (x, y) split its label's slice? (SplitsWithoutCentre, for rays on the view's edge.)
  bool IsArticulation(const std::int32_t* labels, int x, int y, std::int32_t own) const {
    unsigned same = 0;
    for (int row = 0; row < 3; ++row) {
      for (int column = 0; column < 3; ++column) {
        const int nx = x + column - 1, ny = y + row - 1;
        const bool in = nx >= 0 && ny >= 0 && nx < width_ && ny < height_ && labels[ny * width_ + nx] == own;
        same |= static_cast<unsigned>(in) << (4 * row + column);
      }
    }
    return SplitsWithoutCentre(same);
  }

  // Boundary term (Eq. 7) of label k for the ray (x, y) of view (u, v), before the lambda_b / 8 factor: spatial
  // neighbours in this view, angular neighbours at the candidate's rounded disparity in the 8 neighbouring views,
  // and the mixed ones around them.
  // It may stop early, returning a value above `limit`, once the cost exceeds it: after the spatial count and, near
  // the border, after the angular one (inside, the angular and mixed counts come from the same reads).
  // The clique is cut at the image border and at the edge views of the light field; the counts of differing
  // neighbours are rescaled to the full clique (8 spatial, 8 angular, 64 mixed) so that rays there resist label
  // changes as much as anywhere else (otherwise the edge views, with 3 or 5 neighbouring views instead of 8, drift).
  // The angular neighbour sits at a fractional position (x - a d, y - b d); it is read with bilinear weights, so the
  // clique follows the true epipolar line instead of a rounded one (rounding d would favour moving a boundary by
  // round(d) per view step, and the error adds up towards the edge views). Its 3x3 mixed ring is taken around the
  // nearest pixel.
  double BoundaryCost(const SweptView& view, int x, int y, int k, double d, double limit) const {
    const int rounded = RoundHalfAway(d);
    const int reach = std::abs(rounded) + 1;  // the 3x3 blocks of the neighbouring views must lie inside the view
    if (x >= reach && y >= reach && x + reach + 1 < width_ && y + reach < height_) {
      return InteriorBoundaryCost(view, x, y, k, d, rounded, limit);
    }
    return BorderBoundaryCost(view, x, y, k, d, rounded, limit);
  }

  // BoundaryCost where every neighbour of the clique lies inside its view. Each neighbouring view's 3x3 block around
  // the rounded angular neighbour is read once: its ring gives the mixed count and, since the bilinear window of the
  // exact neighbour (within half a pixel of the block's centre) lies inside the block, its 2x2 part the angular one.
  double InteriorBoundaryCost(const SweptView& view, int x, int y, int k, double d, int rounded, double limit) const {
    const int w = width_;
    const double spatial = (8 - RingCount(SameAs3x3(view.labels + y * w + x, w, k))) * p_.pen_spatial;
    if (spatial > limit) return spatial;  // a candidate most of whose own-view neighbours are other labels
    // Along an axis the view does not move on, the angular neighbour is the ray's own position: no bilinear weight.
    constexpr AxisTap kStill{1, 0.0};
    const std::array<AxisTap, 3> tx{Tap(x, -1, d, rounded), kStill, Tap(x, 1, d, rounded)};
    const std::array<AxisTap, 3> ty{Tap(y, -1, d, rounded), kStill, Tap(y, 1, d, rounded)};
    // The mismatch of one row of a bilinear window, by view column and the row's two "same" bits (bit 0: left).
    std::array<std::array<double, 4>, 3> row_mismatch;
    for (std::size_t a = 0; a < 3; ++a) {
      const double weight = tx[a].weight;
      for (unsigned bits = 0; bits < 4; ++bits)
        row_mismatch[a][bits] = (1.0 - weight) * !(bits & 1u) + weight * !(bits & 2u);
    }
    double angular = 0.0;
    int mixed = 0;
    const int centre_offset = y * w + x;
    for (int i = 0; i < view.neighbour_count; ++i) {
      const SweptView::Neighbour& n = view.neighbours[static_cast<std::size_t>(i)];
      // Moving one view step along +u shifts a point by -d (docs/DESIGN.md convention).
      const unsigned same = SameAs3x3(n.labels + centre_offset - (n.b * w + n.a) * rounded, w, k);
      mixed += 8 - RingCount(same);
      const auto column = static_cast<std::size_t>(n.a + 1);
      const AxisTap& row_tap = ty[static_cast<std::size_t>(n.b + 1)];
      // Bit 0 of `low`: (x0, y0), bit 1: (x0 + 1, y0), bit 4: (x0, y0 + 1), bit 5: (x0 + 1, y0 + 1).
      const unsigned low = same >> (row_tap.offset * 4 + tx[column].offset);
      const double top = row_mismatch[column][low & 3u];
      const double bottom = row_mismatch[column][(low >> 4) & 3u];
      angular += (1.0 - row_tap.weight) * top + row_tap.weight * bottom;
    }
    const int views = view.neighbour_count;
    return spatial + Rescaled(angular, views, 8) * p_.pen_angular + Rescaled(mixed, 8 * views, 64) * p_.pen_mixed;
  }

  // Where the bilinear window of an angular neighbour starts along one axis, relative to the top-left of the 3x3
  // block around the rounded neighbour (0 or 1), and the weight of its second pixel. `step` is the view step a (or
  // b) and `at` the ray's x (or y).
  struct AxisTap {
    int offset;
    double weight;
  };
  static AxisTap Tap(int at, int step, double d, int rounded) {
    const double position = at - step * d;
    int first = static_cast<int>(position);
    if (position < first) --first;  // floor
    return {first - (at - step * rounded) + 1, position - first};
  }

  // BoundaryCost near the border of the view, where parts of the clique fall outside it.
  double BorderBoundaryCost(const SweptView& view, int x, int y, int k, double d, int rounded, double limit) const {
    const int w = width_;
    int spatial_valid = 8;
    const int spatial = CountBlock(view.labels, x, y, k, spatial_valid);
    // First the angular neighbours (the heaviest penalty), which usually settle a hopeless candidate; then the
    // mixed ones around them.
    struct Block {
      const std::int32_t* labels;
      int x, y;
    };
    std::array<Block, 8> blocks;
    double angular = 0.0, angular_valid = 0.0;
    for (int i = 0; i < view.neighbour_count; ++i) {
      const SweptView::Neighbour& n = view.neighbours[static_cast<std::size_t>(i)];
      // Moving one view step along +u shifts a point by -d (docs/DESIGN.md convention).
      blocks[static_cast<std::size_t>(i)] = Block{n.labels, x - n.a * rounded, y - n.b * rounded};
      AddBilinear(n.labels, x - n.a * d, y - n.b * d, k, angular, angular_valid);
    }
    const int block_count = view.neighbour_count;
    double cost =
        Rescaled(spatial, spatial_valid, 8) * p_.pen_spatial + Rescaled(angular, angular_valid, 8) * p_.pen_angular;
    if (cost > limit) return cost;
    int mixed = 0, mixed_valid = 0;
    for (int i = 0; i < block_count; ++i) {
      const Block& block = blocks[static_cast<std::size_t>(i)];
      if (block.x >= 1 && block.y >= 1 && block.x + 1 < w && block.y + 1 < height_) {
        const std::int32_t* p = block.labels + block.y * w + block.x;
        mixed += (p[-w - 1] != k) + (p[-w] != k) + (p[-w + 1] != k) + (p[-1] != k) + (p[1] != k) + (p[w - 1] != k) +
                 (p[w] != k) + (p[w + 1] != k);
        mixed_valid += 8;
      } else {
        int valid = 0;
        mixed += CountBlock(block.labels, block.x, block.y, k, valid);
        mixed_valid += valid;
      }
    }
    return cost + Rescaled(mixed, mixed_valid, 64) * p_.pen_mixed;
  }

  // The full clique needs no rescaling (count * full / full is count exactly; the division was 4 % of a sweep).
  static double Rescaled(double count, double valid, int full) {
    if (valid == full) return count;
    return valid > 0 ? count * full / valid : 0.0;
  }

  // Adds the bilinear weights of the pixels around (fx, fy) whose label differs from k to `count`, and the weights
  // of those inside the view to `valid`.
  void AddBilinear(const std::int32_t* labels, double fx, double fy, int k, double& count, double& valid) const {
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
    const double wx = fx - x0, wy = fy - y0;
    for (int j = 0; j <= 1; ++j) {
      const double weight_y = j == 0 ? 1.0 - wy : wy;
      const int y = y0 + j;
      if (weight_y <= 0.0 || y < 0 || y >= height_) continue;
      for (int i = 0; i <= 1; ++i) {
        const double weight = weight_y * (i == 0 ? 1.0 - wx : wx);
        const int x = x0 + i;
        if (weight <= 0.0 || x < 0 || x >= width_) continue;
        valid += weight;
        if (labels[y * width_ + x] != k) count += weight;
      }
    }
  }

  // Labels != k among the 8 neighbours of (x, y) that lie inside the view; `valid` counts those.
  int CountBlock(const std::int32_t* labels, int x, int y, int k, int& valid) const {
    int count = 0;
    valid = 0;
    for (int oy = -1; oy <= 1; ++oy) {
      const int ny = y + oy;
      if (ny < 0 || ny >= height_) continue;
      for (int ox = -1; ox <= 1; ++ox) {
        const int nx = x + ox;
        if ((ox == 0 && oy == 0) || nx < 0 || nx >= width_) continue;
        count += labels[ny * width_ + nx] != k;
        ++valid;
      }
    }
    return count;
  }

  // The energy of the ray with label k; once it is known to exceed `limit` it returns early (a value > limit).
  double Cost(const SweptView& view, int x, int y, std::size_t index, int k, double limit) const {
    const Slice& s = SliceOf(view.cam, k);
    const double inv_n = s.inv_n;
    const float* lab = LabOf(view.cam, index);
    const double dl = lab[0] - s.l * inv_n, da = lab[1] - s.a * inv_n, db = lab[2] - s.b * inv_n;
    // The slice's position centre is where the superpixel's centre-view centroid lands in this view along its
    // plane, so slices clipped by the image border or partly occluded are not pulled towards their visible part.
    const std::size_t sk = static_cast<std::size_t>(k);
    const double dx = x - (centre_x_[sk] - view.du * centre_d_[sk]);
    const double dy = y - (centre_y_[sk] - view.dv * centre_d_[sk]);
    double cost = (dl * dl + da * da + db * db) * inv_colour_ + p_.lambda_p * (dx * dx + dy * dy) * inv_size_;
    if (view.centre) {
      const float d = in_.centre_disparity[index];
      if (std::isfinite(d)) {
        const double e = (d - planes_[static_cast<std::size_t>(k)].AtCentre(x, y)) * inv_range_;
        cost += p_.lambda_d * e * e;
      }
    }
    if (cost > limit) return cost;
    const double boundary_limit =
        boundary_weight_ > 0.0 ? (limit - cost) / boundary_weight_ : std::numeric_limits<double>::infinity();
    cost += boundary_weight_ * BoundaryCost(view, x, y, k, RayDisparity(k, x, y, view.du, view.dv), boundary_limit);
    return cost;
  }

  // Wakes the rays whose energy depends most on the ray (x, y) of view (u, v): its spatial 3x3 and, in each
  // neighbouring view, the rays that see it as their angular neighbour (at the given rounded disparity) and their
  // 4-neighbours (which cover the bilinear partners). Rays that see it only as a mixed neighbour (weight 0.7 of 4)
  // are left asleep: waking all 80 would re-evaluate ten times more rays for little change. Flags of other views
  // may be set by several threads at once, so they are written atomically.
  void Wake(const SweptView& view, int x, int y, int rounded) {
    const int reach = std::abs(rounded) + 1;
    if (x < reach || y < reach || x + reach >= width_ || y + reach >= height_) {
      WakeNearBorder(view, x, y, rounded);
      return;
    }
    const int w = width_;
    std::uint8_t* own = view.flags + y * w + x;
    for (const int offset : {-w - 1, -w, -w + 1, -1, 0, 1, w - 1, w, w + 1}) SetAwake(own + offset);
    for (int i = 0; i < view.neighbour_count; ++i) {
      const SweptView::Neighbour& n = view.neighbours[static_cast<std::size_t>(i)];
      // A ray q of view (u+a, v+b) sees this ray as its angular neighbour when q sits where this ray's scene point
      // appears there, at (x - a d, y - b d).
      std::uint8_t* q = n.flags + (y - n.b * rounded) * w + (x - n.a * rounded);
      for (const int offset : {-w, -1, 0, 1, w}) SetAwake(q + offset);
    }
  }

  // Wake for rays whose 3x3 or angular neighbours' crosses reach past the view's border.
  void WakeNearBorder(const SweptView& view, int x, int y, int rounded) {
    for (int b = -1; b <= 1; ++b) {
      const int nv = view.v + b;
      if (nv < 0 || nv >= shape_.nv) continue;
      for (int a = -1; a <= 1; ++a) {
        const int nu = view.u + a;
        if (nu < 0 || nu >= shape_.nu) continue;
        std::uint8_t* flags = ViewFlags(nv * shape_.nu + nu);
        const int cx = x - a * rounded, cy = y - b * rounded;
        const bool own = a == 0 && b == 0;
        for (int oy = -1; oy <= 1; ++oy) {
          const int ny = cy + oy;
          if (ny < 0 || ny >= height_) continue;
          for (int ox = -1; ox <= 1; ++ox) {
            const int nx = cx + ox;
            if (nx < 0 || nx >= width_ || (!own && ox != 0 && oy != 0)) continue;
            SetAwake(flags + ny * width_ + nx);
          }
        }
      }
    }
  }

  static void SetAwake(std::uint8_t* flag) { __atomic_store_n(flag, std::uint8_t{1}, __ATOMIC_RELAXED); }

  // True if the eight flags from `flags` are all clear. Only the thread sweeping a view writes its flags while it
  // runs (views of one phase are two steps apart, and Wake reaches one step), so a plain read is safe here.
  static bool EightAsleep(const std::uint8_t* flags) {
    std::uint64_t word = 0;
    std::memcpy(&word, flags, sizeof word);
    return word == 0;
  }

  SweptView MakeSweptView(int cam) {
    SweptView view;
    const ViewIndex index = ViewFromCameraNumber(cam, shape_.nu);
    view.cam = cam;
    view.u = index.u;
    view.v = index.v;
    view.du = index.u - centre_.u;
    view.dv = index.v - centre_.v;
    view.centre = index == centre_;
    view.labels = ViewLabels(cam);
    view.flags = ViewFlags(cam);
    for (int b = -1; b <= 1; ++b) {
      for (int a = -1; a <= 1; ++a) {
        const int nu = view.u + a, nv = view.v + b;
        if ((a == 0 && b == 0) || nu < 0 || nu >= shape_.nu || nv < 0 || nv >= shape_.nv) continue;
        const int neighbour = nv * shape_.nu + nu;
        view.neighbours[static_cast<std::size_t>(view.neighbour_count++)] = {ViewLabels(neighbour),
                                                                             ViewFlags(neighbour), a, b};
      }
    }
    return view;
  }

  long long SweepView(int cam, int top, int bottom) {
    const SweptView view = MakeSweptView(cam);
    const bool centre = view.centre;
    const int du = view.du, dv = view.dv;
    std::int32_t* labels = view.labels;
    std::uint8_t* flags = view.flags;
    long long moves = 0;
    for (int y = top; y < bottom; ++y) {
      for (int x = 0; x < width_; ++x) {
        const std::size_t index =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
        if (x % 8 == 0 && x + 8 <= width_ && EightAsleep(flags + index)) {
          x += 7;  // most rays sleep after the first sweeps: skip them a word at a time
          continue;
        }
        if (__atomic_load_n(flags + index, __ATOMIC_RELAXED) == 0) continue;
        __atomic_store_n(flags + index, std::uint8_t{0}, __ATOMIC_RELAXED);
        const std::int32_t own = labels[index];
        // The candidates: the labels of the 4-neighbours, left, right, up, down, each once.
        std::array<std::int32_t, 5> candidates{own, own, own, own, own};
        int count = 1;
        const auto consider = [&](std::int32_t label) {
          for (int i = 0; i < count; ++i) {
            if (candidates[static_cast<std::size_t>(i)] == label) return;
          }
          candidates[static_cast<std::size_t>(count++)] = label;
        };
        bool splits = false;
        if (x >= 1 && y >= 1 && x + 2 < width_ && y + 1 < height_) {  // the block and SameAs3x3's extra label
          const unsigned same = SameAs3x3(labels + index, width_, own);
          if ((same & kEdgeBits) == kEdgeBits) continue;  // interior ray
          const std::int32_t* p = labels + index;
          consider(p[-1]);
          consider(p[1]);
          consider(p[-width_]);
          consider(p[width_]);
          splits = SplitsWithoutCentre(same);
        } else {
          if (x > 0) consider(labels[index - 1]);
          if (x + 1 < width_) consider(labels[index + 1]);
          if (y > 0) consider(labels[index - static_cast<std::size_t>(width_)]);
          if (y + 1 < height_) consider(labels[index + static_cast<std::size_t>(width_)]);
          if (count == 1) continue;  // interior ray
          splits = IsArticulation(labels, x, y, own);
        }
        if (centre && SliceOf(cam, own).n <= 1) continue;  // keep every label in the centre view (ELR = 1)
        if (splits) continue;                              // keep the slice connected
        std::int32_t best = own;
        double best_cost = Cost(view, x, y, index, own, std::numeric_limits<double>::infinity());
        for (int i = 1; i < count; ++i) {
          const std::int32_t k = candidates[static_cast<std::size_t>(i)];
          const double cost = Cost(view, x, y, index, k, best_cost);
          if (cost < best_cost) {
            best_cost = cost;
            best = k;
          }
        }
        if (best == own) continue;
        const float* lab = LabOf(cam, index);
        Add(SliceOf(cam, own), lab, x, y, -1);
        Add(SliceOf(cam, best), lab, x, y, +1);
        labels[index] = best;
        ++moves;
        const int rounded_old = RoundedDisparity(own, x, y, du, dv);
        const int rounded_new = RoundedDisparity(best, x, y, du, dv);
        Wake(view, x, y, rounded_old);
        if (rounded_new != rounded_old) Wake(view, x, y, rounded_new);
      }
    }
    return moves;
  }

  const RefineInputs& in_;
  const LfspParams& p_;
  const LightFieldShape shape_;
  Labels& labels_;
  std::vector<Plane>& planes_;
  const int width_;
  const int height_;
  const std::size_t view_pixels_;
  const ViewIndex centre_;
  std::vector<Slice> slices_;
  std::vector<std::uint8_t> active_;
  std::vector<double> centre_x_, centre_y_, centre_d_;
  double inv_colour_ = 0.0;
  double inv_size_ = 0.0;
  double inv_range_ = 0.0;
  double boundary_weight_ = 0.0;
};

}  // namespace

RefineReport RefineLabels(const RefineInputs& inputs, const LfspParams& params, Labels& labels,
                          std::vector<Plane>& planes) {
  RefineReport report;
  Refiner refiner(inputs, params, labels, planes);
  const double rays = static_cast<double>(labels.size());
  const cv::Mat disparity(labels.shape().height, labels.shape().width, CV_32F,
                          const_cast<float*>(inputs.centre_disparity));
  Progress progress("segment", static_cast<std::size_t>(params.iterations));  // drawn only on a terminal
  for (int iteration = 0; iteration < params.iterations; ++iteration) {
    Stopwatch step;
    const long long moves = refiner.Sweep();
    progress.Tick();
    report.sweep_seconds.push_back(step.Lap());
    report.moves += moves;
    report.moves_per_iteration.push_back(moves);
    ++report.iterations;
    const BoundaryTypeCounts types =
        SmoothPlanes(refiner.CentreLabels(), inputs.superpixels, disparity, inputs.disparity_range, params, planes);
    report.plane_seconds += step.Lap();
    report.occlusion_boundaries = types.occlusion;
    report.hinge_boundaries = types.hinge;
    report.coplanar_boundaries = types.coplanar;
    if (static_cast<double>(moves) < params.convergence * rays) {
      progress.Tick(static_cast<std::size_t>(params.iterations - iteration - 1));  // converged: the rest is not needed
      break;
    }
  }
  return report;
}

}  // namespace lfsp::segment
