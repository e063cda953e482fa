#include "arguments/depth_arguments.h"

#include "lfsp/core/error.h"

namespace lfsp::cli {

void AddDepthArguments(CLI::App* command, DepthArguments& arguments) {
  depth::DepthOptions& method = arguments.method;
  command->add_option(
      "--dmin", arguments.dmin,
      "Smallest disparity (px per view step); default: disp_min of parameters.cfg / bundle metadata, else "
      "estimated from the views (a coarse sweep, logged)");
  command->add_option("--dmax", arguments.dmax, "Largest disparity; default: disp_max of the metadata, else estimated");
  command->add_option("--labels", method.labels, "Number of disparity labels")
      ->capture_default_str()
      ->check(CLI::Range(3, 1024));
  command->add_flag("--no-occlusion", arguments.no_occlusion,
                    "Use all views everywhere (no edge-split of the angular patch); default: off");
  command->add_flag("--wta", arguments.winner_take_all,
                    "Plain winner-take-all on the cost volume: no aggregation, no median (baseline); default: off");
  command->add_flag("--plane-fit", method.plane_fit,
                    "Slanted-plane refinement of textureless pixels per superpixel (antinous: BadPix 0.07 5.9 -> "
                    "5.0 %, but worse on thin occluders); default: off");
  command
      ->add_option(
          "--occlusion-radius", method.occlusion.radius,
          "Pixels within this distance of a centre-view edge use the better half of the views; 0 = "
          "automatic (the largest shift between the centre and an outer view over the disparity range, kept within "
          "2-12 px, plus twice the presmoothing)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option(
          "--halves-agree", method.cost.halves_agree_labels,
          "Near an edge, -1 = the lower envelope of the two halves of the angular patch; N >= 0 = where the two "
          "halves' best labels lie within N labels of each other the whole patch stays, elsewhere only the half "
          "whose best label costs less replaces it (reads thin bars right on clean renderings, but spreads the "
          "foreground on lenslet decodes)")
      ->capture_default_str()
      ->check(CLI::Range(-1, 1024));
  command
      ->add_option("--along-edge-penalty", method.cost.along_edge_penalty,
                   "Near an edge, the views along it replace the whole patch where their cost times this is lower "
                   "(sees into gaps between parallel occluders, e.g. a comb's teeth); 0 = off")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--horizon-slack", method.occluder_horizon.slack,
                   "Near an edge, the partial patches stand in only at disparities below the occluder horizon plus "
                   "this, px per view step: a pixel can be hidden from a view only by a surface nearer than it, "
                   "and nearer by its distance over the longest view offset (the whole patch's disparity says where "
                   "those are). Keeps thin bars and the flat surface beside an occluder from reading too near; < 0 = "
                   "at every disparity")
      ->capture_default_str();
  command
      ->add_option("--horizon-widening", method.occluder_horizon.widening,
                   "Pixels: the whole patch's disparity is widened to its maximum over this radius before the "
                   "horizon is drawn, so a disparity read a little too far beside an edge does not lower it")
      ->capture_default_str()
      ->check(CLI::Range(0, 64));
  command
      ->add_option("--p1", method.sgm.p1,
                   "SGM penalty for a one-label step, in units of the default cost; scaled with the cost's range "
                   "(x0.42 when the automatic detail weight leaves the detail term out of a lenslet decode)")
      ->capture_default_str();
  command
      ->add_option("--p2", method.sgm.p2, "SGM penalty for a larger jump (lowered across colour edges), scaled as --p1")
      ->capture_default_str();
  command
      ->add_option("--excluded-ring", method.cost.excluded_ring,
                   "Leave the views within N steps of the centre out of the cost; -1 = automatic: on a light "
                   "field decoded from a lenslet capture, whose nearby views share sensor pixels and noise, 2 when "
                   "at least 7x7 views remain, 1 with 5x5; 0 otherwise")
      ->capture_default_str()
      ->check(CLI::Range(-1, 16));
  command
      ->add_option("--sampler", arguments.sampler,
                   "How views are resampled at sub-pixel shifts: bilinear (sharpest) | noise-matched (a cubic kernel "
                   "that keeps the same noise at every shift, so noise cannot pull disparities off whole-pixel "
                   "shifts; blurs by the cubic B-spline) | cubic (Keys' cubic convolution: sharp, and blurs no more "
                   "at half-pixel shifts than at whole ones to second order; antinous BadPix 0.07 5.9 -> 4.9 %, but "
                   "worse on sharp-edged renderings such as the simulator's occluders) | automatic: noise-matched on "
                   "lenslet decodes and on views whose median noise estimate reads above 0.003 (noise, or a fine "
                   "sharp texture, whose bilinear resampling is biased too), bilinear on the others")
      ->capture_default_str()
      ->check(CLI::IsMember({"automatic", "bilinear", "noise-matched", "cubic"}));
  command->add_option("--colour-weight", method.cost.colour_weight, "Weight of the colour term of the cost")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option(
          "--channel-weights", arguments.channel_weights,
          "Weights of the red, green and blue differences in the colour term, e.g. 1,1,1; default: "
          "automatic, 1,1,1 on clean views and inversely to each channel's noise variance on noisy ones (a Lytro "
          "decode's colour matrix leaves red and blue several times noisier than green)")
      ->expected(3)
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--detail-weight", method.cost.detail_weight,
                   "Weight of the detail term of the cost (the locally normalised high-pass grey image); -1 = "
                   "automatic: 1 on views that are not presmoothed and on rendered light fields; on a presmoothed "
                   "lenslet decode the band's signal against its noise, m^2 / (m^2 + (16 n)^2), times the share of "
                   "the finest band that is texture (0 below a fine-band signal-to-noise ratio of 4, 1 from 8; "
                   "full-size decodes of weak textures read about 2.6 and leave the term out)")
      ->capture_default_str()
      ->check(CLI::Range(-1.0, 100.0));
  command
      ->add_option("--presmooth", method.presmooth_sigma,
                   "Gaussian smoothing of every view before matching, pixels; -1 = automatic: 0.6 px on noisy views "
                   "(a lenslet decode, or estimated noise above 0.003 by the lower quartile of a plane-free "
                   "filter's response, which a clean view's fine sharp texture does not raise), none on clean ones; "
                   "0 = off")
      ->capture_default_str()
      ->check(CLI::Range(-1.0, 10.0));
  command
      ->add_option("--sub-label-radius", method.sub_label.radius,
                   "Where the semi-global penalty saturates the labels next to the best one (textured surfaces, "
                   "whose aggregated cost's parabola read fronto-parallel strips up to a third of a label step "
                   "towards their nearest label), the sub-label offset comes from the data cost summed over a window "
                   "of this radius, weighted by colour similarity; 0 = the aggregated cost's parabola everywhere")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--median-radius", method.median.radius,
                   "Weighted-median refinement radius (0 = off, the wide window too)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--wide-median-radius", method.median.wide_radius,
                   "Radius of the wide weighted median, which corrects gross errors such as a thin occluder's "
                   "disparity spread over a flat region beside it (occluders: BadPix 0.07 2.27 -> 1.74 %); 0, or "
                   "at most --median-radius, = off")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--wide-median-threshold", method.median.wide_threshold,
                   "The wide median replaces the fine one only where they differ by more than this, px per view "
                   "step (lower corrects more, but biases slanted surfaces)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--fill-smoothness", method.textureless_fill.smoothness,
                   "Textureless fill, last: pixels of flat colour take the disparity interpolated from the textured "
                   "pixels around them on the same surface (a slanted floor of flat tiles reads as a plane instead "
                   "of a staircase; spheres 9x9x512x512: BadPix 0.07 22.9 -> 18.6 %); the weight of smoothness "
                   "against a textured pixel's own estimate; 0 = off")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--fill-jump", method.textureless_fill.jump,
                   "The textureless fill mixes no neighbours whose disparities differ by more than this, px per "
                   "view step (depth edges without a colour edge stay)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--mixed-edge-share", method.mixed_edges.max_share,
                   "Last step: a pixel on the nearer side of an occlusion edge whose colour holds less than this share "
                   "of the nearer surface's, in RGB and in chromaticity, takes the farther side's disparity, so the "
                   "foreground no longer reads a pixel fat (strips up to 2 px wide never move; README, depth); 0 = off")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
}

depth::DepthOptions ToDepthOptions(const DepthArguments& arguments) {
  depth::DepthOptions method = arguments.method;
  if (arguments.dmin.has_value() != arguments.dmax.has_value())
    throw Error("lfsp depth: give both " + OptionName("dmin") + " and " + OptionName("dmax"));
  if (arguments.dmin) method.range = DisparityRange{*arguments.dmin, *arguments.dmax};
  if (arguments.no_occlusion) method.occlusion_handling = false;
  if (arguments.winner_take_all) method.regularise = false;
  method.cost.sampler = depth::SamplerFromString(arguments.sampler);
  if (!arguments.channel_weights.empty()) {
    if (arguments.channel_weights.size() != 3)
      throw Error(OptionName("channel_weights") + " takes three weights: red, green, blue");
    method.cost.channel_weights = {arguments.channel_weights[0], arguments.channel_weights[1],
                                   arguments.channel_weights[2]};
  }
  return method;
}

}  // namespace lfsp::cli
