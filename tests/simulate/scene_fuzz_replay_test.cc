// Replays the scene fuzz target (fuzz/scene_fuzz.cc) over deterministic mutations of every built-in scene's JSON:
// byte flips, deletions, insertions and numbers replaced by extreme values. Nothing but lfsp::Error may escape
// the parser, and accepted scenes must render (a crash or another exception fails the test).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/core/untrusted_json.h"
#include "lfsp/simulate/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace lfsp::simulate {
namespace {

void Feed(const std::string& text) {
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

// Whether the parser accepts `text` as a scene (the fuzz target then renders it).
bool Accepted(const std::string& text) {
  try {
    (void)SceneFromJson(ParseUntrustedJson(text, "fuzz.json"), ".", "fuzz.json");
    return true;
  } catch (const Error&) {
    return false;
  }
}

TEST(SceneFuzzReplay, MutatedBuiltinScenesNeverCrash) {
  std::mt19937 rng(12345);
  const char* extremes[] = {"1e30",         "-1e30", "0",  "-0.0", "1e-30", "9999", "-9999",
                            "123456789012", "\"x\"", "[]", "{}",   "null",  "true", "[1,2,3]"};
  int runs = 0, accepted = 0;
  for (const auto& name : BuiltinSceneNames()) {
    const std::string base = SceneToJson(BuiltinScene(name)).dump();
    Feed(base);
    for (int k = 0; k < 150; ++k, ++runs) {
      std::string text = base;
      const int edits = 1 + static_cast<int>(rng() % 3);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = rng() % text.size();
        switch (rng() % 4) {
          case 0:
            text[at] = static_cast<char>(rng() % 128);
            break;
          case 1:
            text.erase(at, 1 + rng() % 8);
            break;
          case 2:
            text.insert(at, 1, "[]{},:\"0-e."[rng() % 11]);
            break;
          default: {
            // Replace the number starting at or after `at` by an extreme value.
            const std::size_t start = text.find_first_of("-0123456789", at);
            if (start == std::string::npos) break;
            const std::size_t end = text.find_first_not_of("-+.0123456789eE", start);
            text.replace(start, end - start, extremes[rng() % (sizeof extremes / sizeof *extremes)]);
          }
        }
        if (text.empty()) text = "{}";
      }
      Feed(text);
      accepted += Accepted(text) ? 1 : 0;
    }
  }
  EXPECT_EQ(runs, 150 * static_cast<int>(BuiltinSceneNames().size()));
  // Both paths ran: some mutations were refused, and some were accepted and rendered.
  EXPECT_GT(accepted, 0);
  EXPECT_LT(accepted, runs);
  RecordProperty("accepted", accepted);
}

}  // namespace
}  // namespace lfsp::simulate
