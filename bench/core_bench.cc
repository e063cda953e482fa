// Core I/O: loading the HCI views folder and writing / reading the HDF5 bundle (issue 2 targets).

#include <filesystem>

#include "bench_case.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/load.h"
#include "lfsp/core/views_folder.h"

namespace lfsp::bench {
namespace {

std::filesystem::path Antinous() { return std::filesystem::path(SharedDataDir()) / "hci" / "antinous"; }
std::filesystem::path BundlePath() { return std::filesystem::temp_directory_path() / "lfsp_bench_antinous.h5"; }

// Keeps the loaded light field alive across runs of a case (each case runs in its own process).
Bundle& Loaded() {
  static Bundle bundle;
  return bundle;
}

std::string Shape(const LightField& light_field) { return ToString(light_field.shape()); }

}  // namespace

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "core";
  c.name = "load-png-views";
  c.input = "antinous 9x9x512x512 PNG";
  c.target = "<= 0.5 s";
  c.needs_shared_data = true;
  c.run = [] { return Shape(ReadViewsFolder(Antinous())); };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "core";
  c.name = "save-h5-bundle";
  c.input = "antinous 9x9x512x512 float32";
  c.target = "-";
  c.needs_shared_data = true;
  c.prepare = [] { Loaded() = LoadLightField(Antinous()); };
  c.run = [] {
    WriteBundle(Loaded(), BundlePath());
    return std::to_string(std::filesystem::file_size(BundlePath()) >> 20) + " MiB";
  };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "core";
  c.name = "load-h5-bundle";
  c.input = "antinous 9x9x512x512 float32";
  c.target = "<= 0.2 s";
  c.needs_shared_data = true;
  c.baseline = "load-png-views";
  c.prepare = [] {
    if (!std::filesystem::exists(BundlePath())) WriteBundle(LoadLightField(Antinous()), BundlePath());
  };
  c.run = [] { return Shape(ReadBundle(BundlePath()).light_field); };
  return c;
}

}  // namespace lfsp::bench
