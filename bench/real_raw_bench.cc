// Issue 13 on real data: the lenslet lattice of a real F01 raw frame with no white image and no metadata
// (../shared/data/lytro_raw/tao_f01/IMG_1.jpg, 3280x3280), scored against the camera's own table of lens centres.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "bench_case.h"
#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/raw_input.h"

namespace lfsp::bench {
namespace {

struct RealFrame {
  cv::Mat grey;
  decode::GridGuess guess;
  std::vector<std::pair<double, double>> table;  // (x, y) of every lens, 0-based pixels
};

RealFrame& Frame() {
  static RealFrame frame;  // each case runs in its own process
  return frame;
}

void PrepareFrame() {
  const std::string folder = SharedDataDir() + "/lytro_raw/tao_f01/";
  decode::PlainRawOptions options;
  options.camera = "f01";
  const decode::RawInput input = decode::ReadPlainRawImage(folder + "IMG_1.jpg", options);
  RealFrame& frame = Frame();
  frame.grey = decode::WhiteImageToGrey(input.raw, *input.metadata.raw_format, "IMG_1.jpg");
  frame.guess = decode::GuessFromMetadata(input.metadata, input.raw.width, input.raw.height);
  std::ifstream file(folder + "image_cords_rowcol_0based.txt");
  std::string line;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double i = 0, j = 0, row = 0, col = 0;
    if (fields >> i >> j >> row >> col) frame.table.emplace_back(col, row);
  }
}

}  // namespace

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "decode";
  c.name = "grid-capture-f01-real";
  c.input = "real F01 raw JPEG 3280x3280, no white image";
  c.target = "<= 1 s; median <= 0.45 px, p95 <= 0.75 px";
  c.repetitions = 5;
  c.needs_shared_data = true;
  c.prepare = PrepareFrame;
  c.run = [] {
    const RealFrame& frame = Frame();
    const decode::LensletGrid grid =
        decode::FindLensletGrid(frame.grey, frame.guess, decode::LensletImageKind::kCapture).grid;
    std::vector<double> distances;
    distances.reserve(frame.table.size());
    for (const auto& [x, y] : frame.table) {
      int i = 0, j = 0;
      grid.Nearest(x, y, i, j);
      double cx = 0.0, cy = 0.0;
      grid.Centre(i, j, cx, cy);
      distances.push_back(std::hypot(cx - x, cy - y));
    }
    std::sort(distances.begin(), distances.end());
    char text[160];
    std::snprintf(text, sizeof text, "%d x %d lenses; vs camera table median %.3f px, p95 %.3f px", grid.columns,
                  grid.rows, distances[distances.size() / 2], distances[distances.size() * 95 / 100]);
    return std::string(text);
  };
  return c;
}

}  // namespace lfsp::bench
