// Fuzz target: the recolour spec that `lfsp pipeline --recolor` and the workflow's config take as text
// ("at=X,Y+X,Y;ids=A+B;hue=DEG;saturation=F;value=F;feather=PX;space=lch|hsv"), through ParseRecolorSpec, which also
// runs edit's point parser and its adjustment checks. Anything but lfsp::Error escaping it is a finding.

#include <string>

#include "../../decode/fuzz/fuzz_target.h"
#include "lfsp/core/error.h"
#include "pipeline/recolor_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)lfsp::pipeline::ParseRecolorSpec(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const lfsp::Error&) {
  }
  return 0;
}
