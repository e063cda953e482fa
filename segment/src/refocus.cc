#include "lfsp/segment/refocus.h"

#include "lfsp/core/shear.h"

namespace lfsp::segment {

// The paper's refocus level is the opposite of core's shear: level L moves every disparity by +L, a shear by s
// moves it by -s. One implementation of the operation lives in core.
LightField RefocusLightField(const LightField& light_field, double level) {
  ShearOptions options;
  options.weight_outside = false;  // the sweep re-segments colours only; replicated borders as before
  return ShearLightField(light_field, static_cast<float>(-level), options);
}

DisparityMap RefocusDisparity(const DisparityMap& disparity, double level) {
  return ShearDisparity(disparity, static_cast<float>(-level));
}

std::vector<double> DefaultRefocusLevels() { return {-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5}; }

}  // namespace lfsp::segment
