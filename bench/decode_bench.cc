// Decode stage, file-format half: unpacking full-size raw sensor buffers and reading a full-size Illum container
// (every SHA-1 verified). These are the first steps of `lfsp decode`, whose whole budget is 2 s (issue 4).

#include <random>
#include <vector>

#include "bench_case.h"
#include "lfsp/decode/lfp_container.h"
#include "lfsp/decode/raw_packing.h"

namespace lfsp::bench {
namespace {

using decode::RawPacking;

struct RawBuffers {
  std::vector<std::uint16_t> pixels;    // the truth
  std::vector<std::uint8_t> packed;     // what the file holds
  std::vector<std::uint16_t> unpacked;  // output, allocated once
};

RawBuffers& Buffers() {
  static RawBuffers buffers;  // each case runs in its own process
  return buffers;
}

void PrepareRaw(RawPacking packing, std::size_t width, std::size_t height) {
  RawBuffers& b = Buffers();
  std::mt19937 rng(1);
  b.pixels.resize(width * height);
  for (auto& p : b.pixels) p = static_cast<std::uint16_t>(rng() & decode::MaxPixelValue(packing));
  b.packed = decode::PackRaw(packing, b.pixels, "bench");
  b.unpacked.assign(b.pixels.size(), 0);
}

std::string UnpackAndCheck(RawPacking packing) {
  RawBuffers& b = Buffers();
  decode::UnpackRaw(packing, b.packed, b.unpacked, "bench");
  // A sparse check (every 97th pixel and the last) keeps the timing about unpacking; the tests check every pixel.
  for (std::size_t i = 0; i < b.pixels.size(); i += 97) {
    if (b.unpacked[i] != b.pixels[i]) return "MISMATCH";
  }
  return b.unpacked.back() == b.pixels.back() ? "exact" : "MISMATCH";
}

decode::LfpContainer& Container() {
  static decode::LfpContainer container;
  return container;
}
std::vector<std::uint8_t>& ContainerBytes() {
  static std::vector<std::uint8_t> bytes;
  return bytes;
}

}  // namespace

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "decode";
  c.name = "unpack-illum-10bit";
  c.input = "7728x5368 Illum 10-bit (51.9 MB)";
  c.target = "-";
  c.prepare = [] { PrepareRaw(RawPacking::kBits10Illum, 7728, 5368); };
  c.run = [] { return UnpackAndCheck(RawPacking::kBits10Illum); };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "decode";
  c.name = "unpack-f01-12bit";
  c.input = "3280x3280 F01 12-bit (16.1 MB)";
  c.target = "-";
  c.prepare = [] { PrepareRaw(RawPacking::kBits12BigEndian, 3280, 3280); };
  c.run = [] { return UnpackAndCheck(RawPacking::kBits12BigEndian); };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "decode";
  c.name = "parse-illum-container";
  c.input = "LFR with a 51.9 MB raw section, SHA-1s verified";
  c.target = "-";
  c.prepare = [] {
    std::mt19937 rng(2);
    std::vector<std::uint8_t> raw(decode::PackedByteCount(RawPacking::kBits10Illum, 7728u * 5368u));
    for (auto& byte : raw) byte = static_cast<std::uint8_t>(rng());
    decode::LfpContainer container;
    const std::string ref = container.AddBinary(std::move(raw));
    container.AddJson({{"frames", {{{"frame", {{"imageRef", ref}}}}}}}, decode::SectionKind::kMetadata);
    ContainerBytes() = decode::SerializeLfpContainer(container);
  };
  c.run = [] {
    Container() = decode::ParseLfpContainer(ContainerBytes(), "bench.LFR");
    return std::to_string(Container().sections.size()) + " sections";
  };
  return c;
}

}  // namespace lfsp::bench
