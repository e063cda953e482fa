// Replays fuzz inputs through LLVMFuzzerTestOneInput when libFuzzer is not available (gcc builds), so each fuzz
// target runs as a CTest test on the committed corpus.
//
//   fuzz_replay_X CORPUS_DIR_OR_FILE... [--derive-from DIR]
//
// --derive-from also replays, for every file in DIR (the real Lytro files in ../shared/data, which must not be
// copied into this tree), its first KB, truncations and deterministic mutations (bit flips, overwritten
// big-endian length fields, zeroed runs). A missing DIR is skipped with a message.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_target.h"

namespace {

std::vector<std::uint8_t> ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t Run(const std::vector<std::uint8_t>& input) {
  LLVMFuzzerTestOneInput(input.data(), input.size());
  return 1;
}

// Deterministic variants of one real file: cheap, reproducible, and aimed at the container's length/offset logic.
std::size_t Derived(const std::vector<std::uint8_t>& file) {
  std::size_t runs = 0;
  const std::size_t head = std::min<std::size_t>(file.size(), 1024);
  const std::vector<std::uint8_t> first_kb(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(head));
  runs += Run(file);
  runs += Run(first_kb);
  for (const std::size_t cut : {std::size_t{0}, std::size_t{11}, std::size_t{16}, std::size_t{60}, std::size_t{111},
                                std::size_t{112}, std::size_t{500}}) {
    if (cut <= file.size())
      runs += Run(std::vector<std::uint8_t>(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(cut)));
  }
  std::uint32_t state = 12345;
  const auto next = [&state] { return state = state * 1664525u + 1013904223u; };
  for (int i = 0; i < 48; ++i) {
    std::vector<std::uint8_t> mutated = first_kb;
    if (mutated.empty()) break;
    switch (i % 4) {
      case 0:  // flip one bit
        mutated[next() % mutated.size()] ^= static_cast<std::uint8_t>(1u << (next() % 8));
        break;
      case 1:  // overwrite the first section's length with a random big-endian value
        if (mutated.size() >= 32) {
          for (int b = 0; b < 4; ++b) mutated[28 + static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(next());
        }
        break;
      case 2: {  // zero a run (hides magics, shortens JSON)
        const std::size_t at = next() % mutated.size();
        for (std::size_t k = at; k < std::min(mutated.size(), at + 1 + next() % 64); ++k) mutated[k] = 0;
        break;
      }
      case 3:  // random byte anywhere in the header area
        mutated[next() % std::min<std::size_t>(mutated.size(), 128)] = static_cast<std::uint8_t>(next());
        break;
    }
    runs += Run(mutated);
  }
  return runs;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t runs = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--derive-from" && i + 1 < argc) {
      const std::filesystem::path dir = argv[++i];
      std::error_code ec;
      if (!std::filesystem::is_directory(dir, ec)) {
        std::printf("skipping --derive-from %s: not found\n", dir.c_str());
        continue;
      }
      for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.is_regular_file()) runs += Derived(ReadAll(entry.path()));
      }
      continue;
    }
    const std::filesystem::path path = arg;
    if (std::filesystem::is_directory(path)) {
      for (const auto& entry : std::filesystem::directory_iterator(path)) {
        if (entry.is_regular_file()) runs += Run(ReadAll(entry.path()));
      }
    } else {
      runs += Run(ReadAll(path));
    }
  }
  std::printf("replayed %zu inputs without a crash\n", runs);
  return runs > 0 ? 0 : 1;
}
