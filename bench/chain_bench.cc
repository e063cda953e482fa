// The whole Illum chain against the hardware and against today's binary (issue 46).
//
// - `machine-floors`: the two cores' measured memory bandwidth and arithmetic throughput, the denominators of the
//   floors below.
// - `illum-pipeline-reference` / `illum-pipeline`: `lfsp pipeline` on the full-size two-horses Illum capture with
//   the reference build (`make reference`: the commit in bench/REFERENCE) and with this build, one after the other
//   in the same run, so the ratio holds on a noisy machine. The row also says whether this build wrote the same
//   disparity bytes and the same segmentation content (decompressed) as the reference.
// - `illum-pipeline-indexed-whites`: the same after `lfsp whites build` of the capture's white images (the decode
//   then takes the lenslet grid stored for its white image instead of fitting it), against `illum-pipeline`.
// - `illum-breakdown`: one run of each, taken apart per stage and per step inside decode, each step beside its floor
//   (bytes it must touch over the measured bandwidth, or operations over the measured throughput). The table is
//   written as Markdown to $TMPDIR/lfsp_bench_illum_breakdown.md (BENCHMARKS.md copies it).
// - `depth-antinous-reference` / `depth-antinous-command` and `lfsp-antinous-reference` / `lfsp-antinous-command`:
//   `lfsp depth` and `lfsp segment --size 20` on antinous 9x9x512x512 with both builds, the same-run ratios of the
//   issue's depth and LFSP targets.

#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_case.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/stopwatch.h"

namespace lfsp::bench {
namespace {

namespace fs = std::filesystem;

std::string FileBytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// "same" when both files exist and hold the same bytes.
std::string SameBytes(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (ReferenceLfsp().empty() || !fs::exists(a, ec) || !fs::exists(b, ec)) return "n/a";
  return FileBytes(a) == FileBytes(b) ? "same" : "DIFFERENT";
}

// "same content" when both bundles hold the same decompressed datasets (samples, weights, labels, disparity) and
// metadata: the chunks' compression is not the content (issue 46 stores a decode's noise byte planes undeflated).
std::string SameContent(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (ReferenceLfsp().empty() || !fs::exists(a, ec) || !fs::exists(b, ec)) return "n/a";
  const Bundle x = ReadBundle(a), y = ReadBundle(b);
  // Bytes, not values: a NaN disparity equals itself.
  const auto same = [](const auto* p, const auto* q, std::size_t n) { return std::memcmp(p, q, n * sizeof(*p)) == 0; };
  const LightField &lx = x.light_field, &ly = y.light_field;
  bool equal = lx.shape() == ly.shape() && lx.metadata == ly.metadata && lx.transfer == ly.transfer &&
               same(lx.data(), ly.data(), lx.size()) && lx.HasWeights() == ly.HasWeights() &&
               x.disparity.has_value() == y.disparity.has_value() && x.labels.has_value() == y.labels.has_value();
  if (equal && lx.HasWeights()) equal = same(lx.weights().data(), ly.weights().data(), lx.weights().size());
  if (equal && x.disparity)
    equal = x.disparity->width() == y.disparity->width() && x.disparity->height() == y.disparity->height() &&
            same(x.disparity->data(), y.disparity->data(),
                 static_cast<std::size_t>(x.disparity->width()) * static_cast<std::size_t>(x.disparity->height()));
  if (equal && x.labels)
    equal = x.labels->size() == y.labels->size() && same(x.labels->data(), y.labels->data(), x.labels->size());
  return equal ? "same content" : "DIFFERENT content";
}

// ---- the machine ----

struct Machine {
  double copy_gb_s = 0.0;  // bytes read + written per second, all threads, arrays far larger than the caches
  double read_gb_s = 0.0;  // bytes read per second (a sum)
  double gflop_s = 0.0;    // float multiply-adds (2 operations each) per second, all threads, as this build compiles
  int threads = 1;
};

// Best of three: the machine is shared, and a floor wants what the hardware can do, not what a neighbour left.
Machine MeasureMachine() {
  Machine machine;
  machine.threads = omp_get_max_threads();
  const std::size_t n = std::size_t{1} << 26;  // 64 Mi floats: 256 MB per array
  std::vector<float> a(n), b(n), c(n);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i) {
    a[static_cast<std::size_t>(i)] = 0.0f;
    b[static_cast<std::size_t>(i)] = 1.0f + 1e-7f * static_cast<float>(i % 1000);
    c[static_cast<std::size_t>(i)] = 2.0f;
  }
  double sink = 0.0;
  for (int repetition = 0; repetition < 3; ++repetition) {
    Stopwatch stopwatch;
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i)
      a[static_cast<std::size_t>(i)] = b[static_cast<std::size_t>(i)] + 0.5f * c[static_cast<std::size_t>(i)];
    machine.copy_gb_s = std::max(machine.copy_gb_s, 3.0 * 4.0 * static_cast<double>(n) / stopwatch.Seconds() * 1e-9);
    stopwatch.Lap();
    float sum = 0.0f;  // vectorised (omp simd), so the sum measures memory, not one adder's latency
#pragma omp parallel for simd schedule(static) reduction(+ : sum)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i) sum += a[static_cast<std::size_t>(i)];
    machine.read_gb_s = std::max(machine.read_gb_s, 4.0 * static_cast<double>(n) / stopwatch.Seconds() * 1e-9);
    sink += sum;
  }
  // 32 independent multiply-add chains per thread (vectorised by the compiler, as the decode's loops are).
  constexpr int kChains = 32;
  const long steps = 20'000'000;
  for (int repetition = 0; repetition < 3; ++repetition) {
    const Stopwatch stopwatch;
    float total = 0.0f;
#pragma omp parallel reduction(+ : total)
    {
      float chain[kChains];
      for (int k = 0; k < kChains; ++k) chain[k] = 1.0f + 1e-3f * static_cast<float>(k + omp_get_thread_num());
      for (long step = 0; step < steps; ++step)
        for (int k = 0; k < kChains; ++k) chain[k] = chain[k] * 0.9999999f + 1e-7f;
      for (int k = 0; k < kChains; ++k) total += chain[k];
    }
    const double operations = 2.0 * kChains * static_cast<double>(steps) * machine.threads;
    machine.gflop_s = std::max(machine.gflop_s, operations / stopwatch.Seconds() * 1e-9);
    sink += total;
  }
  if (sink == 12345.678) std::printf(" ");  // keeps the measured loops
  return machine;
}

std::string MachineText(const Machine& m) {
  return std::to_string(m.threads) + " threads: copy " + Fixed(m.copy_gb_s, 1) + " GB/s (read+write), sum " +
         Fixed(m.read_gb_s, 1) + " GB/s, " + Fixed(m.gflop_s, 1) + " GFLOP/s (float multiply-add)";
}

// ---- the reference build ----

std::string NoReference() {
  return ReferenceLfsp().empty() ? "no reference build (make reference, or LFSP_BENCH_REFERENCE=path/to/lfsp)" : "";
}

fs::path Capture() { return FullSizeCapture("illum", "two-horses"); }
fs::path PipelineOut(bool reference) {
  return fs::temp_directory_path() / (reference ? "lfsp_bench_chain_reference" : "lfsp_bench_chain_current");
}

// Both builds write into the same folder, then move it aside: the output path is part of segmentation.h5 (its
// metadata names the disparity file), so the two runs' files can then be compared byte for byte.
void RunPipeline(bool reference) {
  const fs::path out = PipelineOut(reference);
  const fs::path work = fs::temp_directory_path() / "lfsp_bench_chain_run";
  fs::remove_all(out);
  fs::remove_all(work);
  const std::string arguments = "pipeline " + Capture().string() + " --out " + work.string();
  if (reference)
    RunLfspBinary(ReferenceLfsp(), arguments);
  else
    RunLfsp(arguments);
  fs::rename(work, out);
}

// Seconds of the decode stage and of its decode proper (absent from a reference that predates the step timings).
std::string DecodeStageText(const fs::path& out) {
  const nlohmann::json summary = ReadJson(out / "summary.json");
  std::string text = "decode stage " + Fixed(summary["timings"]["decode"].get<double>(), 2) + " s";
  if (summary.contains("step_seconds"))
    text += " (decode " + Fixed(summary["step_seconds"]["decode"]["decode"].get<double>(), 2) + ", ground truth " +
            Fixed(summary["step_seconds"]["decode"]["ground_truth"].get<double>(), 2) + ")";
  return text;
}

BenchCase PipelineCase(bool reference) {
  BenchCase c;
  c.stage = "chain";
  c.name = reference ? "illum-pipeline-reference" : "illum-pipeline";
  c.input =
      std::string("Illum 7728x5368 two-horses, simulated capture, defaults") + (reference ? ", reference build" : "");
  c.target = reference ? "baseline (bench/REFERENCE)" : "<= 4.0 s, <= 1.2 GB; decode <= 1.0 s";
  c.baseline = reference ? "" : "illum-pipeline-reference";
  c.repetitions = 3;
  if (reference) c.unavailable = NoReference;  // this build's row runs anyway, without its ratio
  c.setup = [] { Capture(); };
  c.run = [reference] {
    RunPipeline(reference);
    return std::string();
  };
  c.score = [reference] {
    const fs::path out = PipelineOut(reference);
    std::string text = PipelineFigures(out) + "; " + DecodeStageText(out);
    if (!reference) {
      const fs::path base = PipelineOut(true);
      text += "; vs reference: disparity.pfm " + SameBytes(out / "disparity.pfm", base / "disparity.pfm") +
              ", segmentation.h5 " + SameContent(out / "segmentation.h5", base / "segmentation.h5") +
              " (decompressed datasets and metadata)";
    }
    return text;
  };
  return c;
}

// ---- the breakdown ----

struct Step {
  std::string stage, step;
  double seconds = 0.0;
  double bytes = 0.0;       // bytes the step must read and write at the least
  double operations = 0.0;  // arithmetic operations it must do at the least (0: bytes decide)
  std::string floor_basis;  // what the bytes or operations are
};

double Get(const nlohmann::json& object, const char* key) {
  return object.contains(key) && object[key].is_number() ? object[key].get<double>() : 0.0;
}

std::string Seconds(double s) { return s < 0.095 ? Fixed(s, 3) : Fixed(s, 2); }

// The rows: stages and decode's steps from the run's summaries, with floors from the sizes involved.
std::vector<Step> Breakdown(const fs::path& out, const nlohmann::json& decode_command) {
  const nlohmann::json summary = ReadJson(out / "summary.json");
  const nlohmann::json depth = ReadJson(out / "disparity.summary.json");
  const nlohmann::json segment = ReadJson(out / "segmentation.summary.json");
  const nlohmann::json& decode = summary["decode"];
  const nlohmann::json& grid = decode["grid"];
  const double pixels = grid["sensor_width"].get<double>() * grid["sensor_height"].get<double>();  // P
  const nlohmann::json& field = decode["light_field"];
  const double rays_all = field["nu"].get<double>() * field["nv"].get<double>() * field["width"].get<double>() *
                          field["height"].get<double>();  // R: every decoded ray
  const double views = summary["views"]["n"].get<double>();
  const double rays = views * views * field["width"].get<double>() * field["height"].get<double>();  // the 9x9 kept
  const double centre = field["width"].get<double>() * field["height"].get<double>();
  const double file = static_cast<double>(fs::file_size(Capture()));
  const nlohmann::json& seconds = decode["seconds"];
  const nlohmann::json& steps = decode["decode"]["seconds"];
  const nlohmann::json& stage_steps = summary["step_seconds"]["decode"];
  std::vector<Step> rows;
  const auto add = [&](const char* stage, const char* step, double s, double bytes, double operations,
                       const std::string& basis) {
    rows.push_back({stage, step, s, bytes, operations, basis});
  };
  // Decode: P sensor pixels (uint16 2 B, float 4 B, RGB float 12 B), R rays (RGB float 12 B + weight 4 B).
  add("decode", "read", Get(seconds, "read"), 2 * file, 0, "the container once read, once copied (SHA-1 aside)");
  add("decode", "unpack", Get(seconds, "unpack"), 1.25 * pixels + 2 * pixels, 0, "10-bit packed in, uint16 out");
  add("decode", "white image", Get(seconds, "white_image"), 3.25 * pixels, 0, "the white raw read and unpacked");
  add("decode", "white preparation + grid", Get(seconds, "white_preparation_and_grid"), (2 + 4 + 4) * pixels, 0,
      "white in, inverse and grey floats out");
  add("decode", "levels, hot pixels, devignetting", Get(steps, "levels_hot_pixels_devignette"), (2 + 4 + 4) * pixels, 0,
      "raw and inverse in, float Bayer out");
  add("decode", "demosaic", Get(steps, "demosaic"), (4 + 4 + 1 + 12) * pixels, 0,
      "Bayer, white grey and lens labels in, RGB float out");
  add("decode", "exposure (white balance, brightest)", Get(steps, "exposure"), (12 + 4) * pixels, 0,
      "RGB and white grey read once");
  add("decode", "slicing", Get(steps, "allocate_wait") + Get(steps, "slice"), (12 + 4 + 1) * pixels + 16 * rays_all, 0,
      "sensor RGB, grey, labels in; R rays RGB + weight out");
  add("decode", "lattice gain", Get(steps, "flatten_lattice"), (16 + 12) * rays_all, 0, "rays read, RGB rewritten");
  add("decode", "softening + colour encoding", Get(steps, "soften_encode"), 24 * rays_all, 0, "RGB read and rewritten");
  add("decode", "view quality figures", Get(steps, "view_quality"), 12 * rays_all, 0, "the rays read once");
  add("decode", "round to uint16 storage", Get(decode["seconds"], "round_to_storage"), 32 * rays_all, 0,
      "RGB + weights read and rewritten");
  add("decode", "ground truth (simulated input only)", Get(stage_steps, "ground_truth"), 20 * rays_all, 0,
      "the ideal light field, labels, weights written from the bundle");
  add("decode", "select 9x9 views", Get(stage_steps, "select_views"), 32 * rays, 0, "9x9 views copied");
  double itemised = 0.0;
  for (const Step& row : rows) itemised += row.seconds;
  add("decode", "(the rest: white database, logging, summary)", summary["timings"]["decode"].get<double>() - itemised,
      0, 0, "");
  if (decode_command.is_object())
    add("decode", "write (lfsp decode's .h5, gzip 1)", Get(decode_command["seconds"], "write"),
        8 * rays_all + 4 * rays_all, 0, "uint16 RGB + weights deflated, 15x15 views");
  // Depth: the cost volume alone reads every view at every label: per ray and label a bilinear RGB sample (12
  // multiply-adds) and its difference (3): 30 operations.
  const double labels = depth["parameters"]["labels"].get<double>();
  const nlohmann::json& depth_steps = depth["timings_seconds"];
  add("depth", "cost volume", Get(depth_steps, "cost_volume"), 12 * rays, 30 * rays * labels,
      "30 operations per ray and label");
  add("depth", "semi-global aggregation", Get(depth_steps, "semi_global"), 0, 8 * 4 * centre * labels,
      "8 paths x 4 operations per pixel and label");
  add("depth", "rest of depth",
      Get(depth_steps, "estimate") - Get(depth_steps, "cost_volume") - Get(depth_steps, "semi_global"), 0, 0, "");
  add("depth", "write", Get(depth_steps, "write"), 3 * 4 * centre, 0, "disparity, confidence, preview");
  // LFSP: each iteration reads every ray's colour and label and writes its label.
  const nlohmann::json& lfsp_steps = segment["timings_seconds"];
  const double iterations = segment["iterations"].get<double>();
  add("segment", "LFSP (size 20)", Get(lfsp_steps, "segmentation"), iterations * (12 + 4 + 4) * rays, 0,
      "per iteration: RGB + label read, label written, every ray");
  add("segment", "write (segmentation.h5, overlays)", Get(lfsp_steps, "write"), (6 + 2 + 4) * rays, 0,
      "uint16 RGB + weights + labels deflated");
  for (const char* stage : {"refocus", "evaluate", "report"})
    add(stage, "", summary["timings"].contains(stage) ? summary["timings"][stage].get<double>() : 0.0, 0, 0, "");
  return rows;
}

std::string BreakdownTable(const std::vector<Step>& rows, const Machine& machine, double wall) {
  std::string table = "| stage | step | s | floor s | x floor | floor from |\n|---|---|---|---|---|---|\n";
  double floors = 0.0;
  for (const Step& row : rows) {
    const double by_bytes = row.bytes / (machine.copy_gb_s * 1e9);
    const double by_operations = row.operations / (machine.gflop_s * 1e9);
    const double floor = std::max(by_bytes, by_operations);
    floors += floor;
    std::string from = row.floor_basis;
    if (floor > 0.0)
      from = (by_operations > by_bytes ? Fixed(row.operations * 1e-9, 1) + " G operations: "
                                       : Fixed(row.bytes * 1e-6, 0) + " MB: ") +
             from;
    table += "| " + row.stage + " | " + row.step + " | " + Seconds(row.seconds) + " | " +
             (floor > 0.0 ? Seconds(floor) : "-") + " | " + (floor > 0.0 ? "x" + Fixed(row.seconds / floor, 0) : "-") +
             " | " + from + " |\n";
  }
  table += "| all | wall | " + Seconds(wall) + " | " + Seconds(floors) + " | x" + Fixed(wall / floors, 0) +
           " | the floors' sum |\n";
  return table;
}

}  // namespace

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "chain";
  c.name = "machine-floors";
  c.input = "3 arrays of 256 MB; 32 multiply-add chains per thread";
  c.target = "- (the floors' denominators)";
  c.repetitions = 1;
  c.run = [] { return MachineText(MeasureMachine()); };
  return c;
}

LFSP_BENCH_CASE { return PipelineCase(true); }
LFSP_BENCH_CASE { return PipelineCase(false); }

// ---- the same capture with its white images indexed ----

// The capture's folder (capture, whites/, ground_truth/) as hard links, so that a whites.json written there does not
// reach the other rows' decodes of the shared capture.
fs::path IndexedCaptureFolder() {
  const fs::path source = Capture().parent_path();
  const fs::path linked = fs::temp_directory_path() / "lfsp_bench_chain_indexed_capture";
  fs::remove_all(linked);
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(source)) {
    const fs::path target = linked / fs::relative(entry.path(), source);
    if (entry.is_directory())
      fs::create_directories(target);
    else {
      fs::create_directories(target.parent_path());
      fs::create_hard_link(entry.path(), target);
    }
  }
  return linked;
}

fs::path IndexedPipelineOut() { return fs::temp_directory_path() / "lfsp_bench_chain_indexed"; }

// `illum-pipeline-indexed-whites`: the pipeline after `lfsp whites build` of the capture's whites/ folder (untimed:
// a camera's white images are indexed once, and the lenslet grid fitted on each), so the decode takes the stored
// grid instead of fitting one. Its outputs must be the plain row's.
BenchCase IndexedWhitesCase() {
  BenchCase c;
  c.stage = "chain";
  c.name = "illum-pipeline-indexed-whites";
  c.input = "Illum 7728x5368 two-horses, simulated capture, defaults, after lfsp whites build";
  c.target = "<= 4.0 s, <= 1.2 GB; decode <= 1.0 s";
  c.baseline = "illum-pipeline";
  c.repetitions = 3;
  c.setup = [] { RunLfsp("whites build " + (IndexedCaptureFolder() / "whites").string()); };
  c.run = [] {
    const fs::path capture = fs::temp_directory_path() / "lfsp_bench_chain_indexed_capture" / Capture().filename();
    fs::remove_all(IndexedPipelineOut());
    RunLfsp("pipeline " + capture.string() + " --out " + IndexedPipelineOut().string());
    return std::string();
  };
  c.score = [] {
    const fs::path out = IndexedPipelineOut(), plain = PipelineOut(false);
    const nlohmann::json summary = ReadJson(out / "summary.json");
    std::error_code ec;
    const std::string same = !fs::exists(plain / "disparity.pfm", ec)                                 ? "n/a"
                             : FileBytes(out / "disparity.pfm") == FileBytes(plain / "disparity.pfm") ? "same"
                                                                                                      : "DIFFERENT";
    return PipelineFigures(out) + "; " + DecodeStageText(out) + "; grid from " +
           summary["decode"]["grid_source"].get<std::string>() + "; disparity.pfm vs illum-pipeline's: " + same;
  };
  return c;
}

LFSP_BENCH_CASE { return IndexedWhitesCase(); }

namespace {

// The two builds' seconds of each run of the alternating case, in its own process.
std::vector<double>& AlternatingSeconds(bool reference) {
  static std::vector<double> seconds[2];
  return seconds[reference ? 1 : 0];
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n == 0 ? 0.0 : (n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]));
}

}  // namespace

// The same two runs alternated, reference first in odd repetitions and second in even ones, so a change of load on
// the shared machine falls on both builds alike; the quality column gives each build's median and their ratio.
LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "chain";
  c.name = "illum-pipeline-alternating";
  c.input = "Illum 7728x5368 two-horses, simulated capture: reference and this build alternated, per repetition";
  c.target = "ratio < 1";
  c.repetitions = 3;
  c.unavailable = NoReference;
  c.setup = [] { Capture(); };
  c.run = [] {
    static int repetition = 0;
    const bool reference_first = repetition++ % 2 == 0;
    for (const bool reference : {reference_first, !reference_first}) {
      const Stopwatch stopwatch;
      RunPipeline(reference);
      AlternatingSeconds(reference).push_back(stopwatch.Seconds());
    }
    return std::string();
  };
  c.score = [] {
    const double reference = Median(AlternatingSeconds(true)), current = Median(AlternatingSeconds(false));
    std::string pairs;
    for (std::size_t i = 0; i < AlternatingSeconds(true).size(); ++i)
      pairs += (i ? " " : "") + Fixed(AlternatingSeconds(false)[i] / AlternatingSeconds(true)[i], 2);
    return "reference " + Fixed(reference, 2) + " s, this build " + Fixed(current, 2) + " s: x" +
           Fixed(current / reference, 2) + " (pair by pair: " + pairs + ")";
  };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "chain";
  c.name = "illum-breakdown";
  c.input = "Illum 7728x5368 two-horses, simulated capture: pipeline + decode command, one run";
  c.target = "table in $TMPDIR/lfsp_bench_illum_breakdown.md";
  c.repetitions = 1;
  c.setup = [] { Capture(); };
  c.run = [] {
    const Machine machine = MeasureMachine();
    RunPipeline(false);
    const fs::path decoded = fs::temp_directory_path() / "lfsp_bench_chain_decoded.h5";
    RunLfsp("decode " + Capture().string() + " --out " + decoded.string());
    const nlohmann::json decode_command = ReadJson(fs::temp_directory_path() / "lfsp_bench_chain_decoded.summary.json");
    fs::remove(decoded);
    const fs::path out = PipelineOut(false);
    const double wall = ReadJson(out / "summary.json")["wall_seconds"].get<double>();
    const std::string table = BreakdownTable(Breakdown(out, decode_command), machine, wall);
    const fs::path path = fs::temp_directory_path() / "lfsp_bench_illum_breakdown.md";
    std::ofstream(path) << "Machine: " << MachineText(machine) << "\n\n" << table;
    return "pipeline wall " + Fixed(wall, 2) + " s; " + MachineText(machine) + "; table: " + path.string();
  };
  return c;
}

namespace {

// `lfsp depth` / `lfsp segment --size 20` on antinous 9x9x512x512 (.h5, made once), with either build.
fs::path AntinousBundle() { return fs::temp_directory_path() / "lfsp_bench_load_antinous.h5"; }
fs::path Antinous() { return fs::path(SharedDataDir()) / "hci" / "antinous"; }
fs::path CommandOut(const std::string& name) { return fs::temp_directory_path() / ("lfsp_bench_chain_" + name); }

BenchCase AntinousCommand(const std::string& what, bool reference) {
  const bool depth = what == "depth";
  const std::string base = (depth ? "depth" : "lfsp") + std::string("-antinous");
  BenchCase c;
  c.stage = "chain";
  c.name = base + (reference ? "-reference" : "-command");
  c.input = std::string("antinous 9x9x512x512 (.h5), `lfsp ") +
            (depth ? "depth`" : "segment --size 20`, GT disparity") + (reference ? ", reference build" : "");
  c.target = reference ? "baseline (bench/REFERENCE)" : (depth ? "estimate <= 1.2 s" : "LFSP <= 1.1 s");
  c.baseline = reference ? "" : base + "-reference";
  c.repetitions = 3;
  c.needs_shared_data = true;
  if (reference) c.unavailable = NoReference;
  c.setup = [] {
    if (!fs::exists(AntinousBundle())) RunLfsp("convert " + Antinous().string() + " " + AntinousBundle().string());
  };
  const fs::path out = CommandOut(c.name) += depth ? ".pfm" : ".h5";
  c.run = [depth, reference, out] {
    const std::string arguments = depth ? "depth " + AntinousBundle().string() + " --out " + out.string()
                                        : "segment " + AntinousBundle().string() + " --disparity " +
                                              (Antinous() / "gt_disp_lowres.pfm").string() + " --size 20 --out " +
                                              out.string();
    if (reference)
      RunLfspBinary(ReferenceLfsp(), arguments);
    else
      RunLfsp(arguments);
    return std::string();
  };
  c.score = [depth, reference, out, base] {
    fs::path summary_path = out;
    summary_path.replace_extension(".summary.json");
    const nlohmann::json summary = ReadJson(summary_path);
    const nlohmann::json& timings = summary["timings_seconds"];
    std::string text;
    if (depth) {
      text =
          "estimate " +
          Fixed(timings.contains("estimate") ? timings["estimate"].get<double>() : timings["stage"].get<double>(), 2) +
          " s";
      if (summary.contains("metrics_vs_input_ground_truth")) {
        const nlohmann::json& all = summary["metrics_vs_input_ground_truth"]["all"];
        text += "; BadPix0.07 " + Fixed(all["badpix_0.07"].get<double>(), 2) + " %, MSEx100 " +
                Fixed(all["mse_x100"].get<double>(), 2);
      }
    } else {
      text = "LFSP " + Fixed(timings["segmentation"].get<double>(), 2) + " s, " +
             std::to_string(summary["superpixels"].get<int>()) + " superpixels";
    }
    if (!reference) {
      const fs::path base_out = CommandOut(base + "-reference") += depth ? ".pfm" : ".h5";
      // A segmentation bundle is compared by its decompressed datasets: its sample type may differ
      // (CompactBundleOptions).
      text += "; vs reference: " + (depth ? SameBytes(out, base_out) : SameContent(out, base_out));
    }
    return text;
  };
  return c;
}

}  // namespace

LFSP_BENCH_CASE { return AntinousCommand("depth", true); }
LFSP_BENCH_CASE { return AntinousCommand("depth", false); }
LFSP_BENCH_CASE { return AntinousCommand("lfsp", true); }
LFSP_BENCH_CASE { return AntinousCommand("lfsp", false); }

}  // namespace lfsp::bench
