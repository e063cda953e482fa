// Simulator: rendering a full-size Illum raw capture (issue 3 target: <= 15 s on 2 cores) and an ideal light field
// of the size the depth/segment tests use.

#include <cmath>
#include <cstdio>
#include <string>

#include "bench_case.h"
#include "lfsp/simulate/raw_capture.h"
#include "lfsp/simulate/render.h"

namespace lfsp::bench {
namespace {

// Mean raw value inside the micro-images, as a sanity figure (a black or saturated capture would show).
std::string MeanLevel(const simulate::RawCapture& raw) {
  double sum = 0;
  for (const auto p : raw.pixels) sum += p;
  char text[64];
  std::snprintf(text, sizeof text, "mean DN %.1f", sum / static_cast<double>(raw.pixels.size()));
  return text;
}

}  // namespace

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "simulate";
  c.name = "illum-raw-capture";
  c.input = "Illum 7728x5368 raw, scene planes";
  c.target = "<= 15 s";
  c.repetitions = 3;
  c.run = [] {
    const auto camera = simulate::CameraPreset("illum");
    const auto raw = simulate::RenderRawCapture(simulate::BuiltinScene("planes"), camera, {});
    return MeanLevel(raw);
  };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "simulate";
  c.name = "illum-white-image";
  c.input = "Illum 7728x5368 white image";
  c.target = "-";
  c.repetitions = 3;
  c.run = [] { return MeanLevel(simulate::RenderWhiteImage(simulate::CameraPreset("illum"), 0, 1)); };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "simulate";
  c.name = "ideal-lf-9x9x256";
  c.input = "9x9x256x256, scene occluders, 3x3 AA";
  c.target = "-";
  c.run = [] {
    simulate::RenderOptions options;
    options.width = options.height = 256;
    const auto r = simulate::RenderLightField(simulate::BuiltinScene("occluders"), options);
    return ToString(r.light_field.shape());
  };
  return c;
}

}  // namespace lfsp::bench
