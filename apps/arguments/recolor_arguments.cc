#include "arguments/recolor_arguments.h"

#include "lfsp/core/error.h"

namespace lfsp::cli {

void AddRecolorArguments(CLI::App* command, RecolorArguments& arguments) {
  command->add_option("--hue", arguments.hue, "Rotate the hue by this many degrees (default: 0)");
  command->add_option("--saturation", arguments.saturation, "Multiply saturation (chroma in lch) by this (default: 1)");
  command->add_option("--value", arguments.value, "Multiply value (lightness L* in lch) by this (default: 1)");
  command->add_option("--space", arguments.space,
                      "Colour space of the edit: lch (perceptual CIE L*C*h via OpenCV) or hsv (default: lch)");
  command->add_option("--feather", arguments.feather,
                      "Soft transition over this many pixels into neighbouring superpixels, per view, scaled by the "
                      "ray weights when the input has them (default: 0, hard edges)");
  command->add_flag("--no-weights", arguments.no_weights,
                    "Do not scale the feather band by the input's ray weights (default: scale when present)");
}

edit::RecolorOptions ToRecolorOptions(const RecolorArguments& arguments) {
  edit::RecolorOptions recolor;
  recolor.adjustment.hue_degrees = arguments.hue;
  recolor.adjustment.saturation = arguments.saturation;
  recolor.adjustment.value = arguments.value;
  recolor.adjustment.space = edit::ColourSpaceFromString(arguments.space);
  recolor.feather_px = arguments.feather;
  recolor.use_ray_weights = !arguments.no_weights;
  edit::ValidateAdjustment(recolor.adjustment);
  if (!(arguments.feather >= 0.0f)) throw Error(OptionName("feather") + ": expected a width >= 0 pixels");
  return recolor;
}

}  // namespace lfsp::cli
