// Issue 49: Bayer mosaics stored as greyscale JPEG. A simulated full-size F01 capture written the way the real F01
// frames of ../shared/data/lytro_raw were (dark, 8 bits, quality 75), decoded with the JPEG restoration, against the
// truth and beside the same mosaic stored losslessly and decoded the plain way; and the real frames themselves.

#include <cstdio>
#include <filesystem>

#include "bench_case.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/decode/capture_decoder.h"
#include "lfsp/decode/view_quality.h"
#include "lfsp/simulate/simulate.h"

namespace lfsp::bench {
namespace {

namespace fs = std::filesystem;

struct SimulatedJpeg {
  fs::path folder;
  LightField truth;
  std::string baselines;  // the lossless and plain decodes' figures
};

SimulatedJpeg& Simulated() {
  static SimulatedJpeg simulated;  // each case runs in its own process
  return simulated;
}

decode::CaptureDecodeResult DecodeMosaic(const fs::path& mosaic, int restore_iterations,
                                         decode::JpegGrey grey = decode::JpegGrey::kSensor) {
  decode::CaptureDecodeOptions options;
  options.plain.camera = "f01";
  options.plain.jpeg_restore_iterations = restore_iterations;
  options.plain.jpeg_grey = grey;
  options.decode.colour = decode::ColourMode::kLinear;
  return decode::DecodeCaptureFile(mosaic, options);
}

std::string Figures(const char* name, const decode::CaptureDecodeResult& result, const LightField& truth) {
  const decode::CentreFidelity fidelity = decode::CompareCentreWithTruth(result.light_field, truth);
  char text[160];
  std::snprintf(text, sizeof text, "%s %.2f dB, chroma err %.4f, bands %.2f", name, fidelity.psnr_db,
                fidelity.chroma_error,
                decode::ChromaBandRatio(result.light_field, result.light_field.shape().Centre()));
  return text;
}

// Simulates `scene` as an F01 capture whose mosaic is also written as the real frames were (8 bits, quality 75).
void PrepareSimulated(const std::string& scene, double exposure) {
  SimulatedJpeg& simulated = Simulated();
  simulated.folder = fs::temp_directory_path() / ("lfsp-bench-jpeg-mosaic-" + scene);
  fs::remove_all(simulated.folder);
  simulate::SimulateOptions options;
  options.camera = "f01";
  options.scene = scene;
  options.capture.exposure = exposure;
  options.mosaic_jpeg_quality = 75;
  options.white_images = false;
  (void)simulate::Simulate(options, simulated.folder);
  simulated.truth = ReadBundle(simulated.folder / "ground_truth" / "decoded.h5").light_field;
  simulated.baselines =
      Figures("lossless", DecodeMosaic(simulated.folder / "capture_mosaic.png", 0), simulated.truth) + "; " +
      Figures("plain JPEG", DecodeMosaic(simulated.folder / "capture_mosaic.jpg", 0), simulated.truth);
}

std::string RestoredBesideBaselines(decode::JpegGrey grey) {
  const SimulatedJpeg& simulated = Simulated();
  return Figures("restored", DecodeMosaic(simulated.folder / "capture_mosaic.jpg", 30, grey), simulated.truth) + "; " +
         simulated.baselines;
}

// A simulated capture's JPEG mosaic, restored, beside its lossless and plain decodes.
BenchCase SimulatedJpegCase(const std::string& name, const std::string& input, const std::string& scene,
                            double exposure, decode::JpegGrey grey = decode::JpegGrey::kSensor) {
  BenchCase c;
  c.stage = "decode";
  c.name = name;
  c.input = input;
  c.target = "bands <= lossless + 0.5; PSNR loss <= 2.5 dB";
  c.repetitions = 1;
  c.prepare = [scene, exposure] { PrepareSimulated(scene, exposure); };
  c.run = [grey] { return RestoredBesideBaselines(grey); };
  return c;
}

}  // namespace

// Exposure 0.3: the mosaic's median code about 20 of 255, as dark as the real frames.
LFSP_BENCH_CASE {
  return SimulatedJpegCase("jpeg-mosaic-f01",
                           "simulated F01 two-horses 3280x3280, exposure 0.3, 8-bit JPEG q75 -> 9x9x379x378",
                           "two-horses", 0.3);
}

// The scene whose JPEG shows the real frames' bands (simulate/src/builtin_scenes.cc).
LFSP_BENCH_CASE {
  return SimulatedJpegCase(
      "jpeg-mosaic-f01-leaves",
      "simulated F01 leaves (large smooth leaves in shade) 3280x3280, exposure 1.8, 8-bit JPEG q75", "leaves", 1.8);
}

// The same two captures restored about the scene's grey (`--jpeg-grey scene`).
LFSP_BENCH_CASE {
  return SimulatedJpegCase("jpeg-mosaic-f01-scene-grey",
                           "as jpeg-mosaic-f01, restored about the scene's grey (--jpeg-grey scene)", "two-horses", 0.3,
                           decode::JpegGrey::kScene);
}

LFSP_BENCH_CASE {
  return SimulatedJpegCase("jpeg-mosaic-f01-leaves-scene-grey",
                           "as jpeg-mosaic-f01-leaves, restored about the scene's grey (--jpeg-grey scene)", "leaves",
                           1.8, decode::JpegGrey::kScene);
}

namespace {

// The real frames, restored about the sensor's grey (the default) or the scene's.
BenchCase RealFramesCase(const std::string& name, const std::string& input, decode::JpegGrey grey) {
  BenchCase c;
  c.stage = "decode";
  c.name = name;
  c.input = input;
  c.target = "chroma bands <= 3.0 each";
  c.repetitions = 1;
  c.needs_shared_data = true;
  c.run = [grey] {
    std::string text;
    for (const char* frame : {"IMG_1.jpg", "IMG_2.jpg", "IMG_3.jpg"}) {
      decode::CaptureDecodeOptions options;
      options.plain.camera = "f01";
      options.plain.jpeg_grey = grey;
      const decode::CaptureDecodeResult result =
          decode::DecodeCaptureFile(fs::path(SharedDataDir()) / "lytro_raw" / "tao_f01" / frame, options);
      char figures[96];
      std::snprintf(figures, sizeof figures, "%s%s bands %.2f / luma %.2f", text.empty() ? "" : "; ", frame,
                    result.summary["decode"]["centre_bands"]["chroma"].get<double>(),
                    result.summary["decode"]["centre_bands"]["luma"].get<double>());
      text += figures;
    }
    return text;
  };
  return c;
}

}  // namespace

LFSP_BENCH_CASE {
  return RealFramesCase("real-f01-jpeg-frames", "IMG_1-3 of lytro_raw/tao_f01 (real F01 JPEG mosaics), default decode",
                        decode::JpegGrey::kSensor);
}

LFSP_BENCH_CASE {
  return RealFramesCase("real-f01-jpeg-frames-scene-grey",
                        "IMG_1-3, restored about the scene's grey (--jpeg-grey scene)", decode::JpegGrey::kScene);
}

}  // namespace lfsp::bench
