#include "arguments/decode_arguments.h"

#include "lfsp/core/error.h"

namespace lfsp::cli {

void AddDecodeArguments(CLI::App* command, DecodeArguments& arguments) {
  command->add_option("--white-images", arguments.white_images,
                      "Folder of white images, MOD_*.RAW + .TXT or calibration archives data.C.* (default: the "
                      "capture's folder, searched recursively, so its whites/ sub-folder is found); a whites.json "
                      "there (lfsp whites build) spares reading again the white images it indexed, and holds their "
                      "lenslet grids");
  command->add_flag("--no-white-image", arguments.no_white_image,
                    "Estimate the white image (micro-image vignetting) and the lenslet grid from the capture itself "
                    "instead of looking one up (automatic, with a warning, when no white image matches; always for "
                    "plain raw images)");
  AddGridFileOption(command, arguments.grid);
  AddPlainRawOptions(command, arguments.plain);
  command->add_option("--demosaic", arguments.demosaic, "gradient | edge-aware | bilinear (default: gradient)");
  command->add_option("--colour", arguments.colour,
                      "camera (white balance, colour matrix, exposure bias, sRGB) | linear (devignetted scene-linear "
                      "RGB) (default: camera)");
  command->add_option("--white-balance", arguments.white_balance,
                      "With --colour camera: auto (the capture's own near-grey pixels, starting from the camera's "
                      "gains) | camera (the file's gains) | none | R,G,B gains (default: camera for Lytro files, "
                      "auto for plain raw images, whose nominal gains belong to another scene's light)");
  command->add_flag("--no-hot-pixels", arguments.no_hot_pixels, "Skip hot-pixel correction (default: corrected)");
  command->add_option("--dehex", arguments.dehex,
                      "Row-alternation softening against hexagonal artefacts, 0..0.25 (default: 0.1)");
  command->add_flag("--no-lattice-flattening", arguments.no_lattice_flattening,
                    "Keep the gain the lens lattice leaves in each view (a devignetting error tied to where each lens "
                    "centre falls on the Bayer tile, the same in every view); default: measured and divided out, "
                    "its size in the summary's decode.lattice_gain");
  command->add_flag("--no-jpeg-block-flattening", arguments.no_jpeg_block_flattening,
                    "Mosaics stored as JPEG: keep the gain each view takes from where its samples fall in the JPEG's "
                    "8x8 blocks (horizontal bands every 13-14 rows on an F01); default: measured and divided out, its "
                    "size in the summary's decode.jpeg_block_gain");
  command
      ->add_option("--views", arguments.views,
                   "Decode only the central N x N views; 0 = those the other stages keep by default (every view "
                   "well lit, judged from the white image before slicing, with a margin), as `lfsp pipeline` does; "
                   "-1 = every view of the lattice's grid (default)")
      ->check(CLI::Range(-1, 1000));
}

void AddGridFileOption(CLI::App* command, std::string& grid_file) {
  command
      ->add_option("--grid", grid_file,
                   "Use this lenslet grid instead of fitting one: lfsp's grid.json (lfsp grid --out) or LFToolbox's "
                   "LensletGridModel (a CalInfo.json or a white image's .grid.json) (default: the grid lfsp whites "
                   "build stored for the white image, else fitted on it, or found in the capture)")
      ->check(CLI::ExistingFile);
}

decode::CaptureDecodeOptions ToCaptureDecodeOptions(const DecodeArguments& arguments) {
  decode::CaptureDecodeOptions options;
  options.white_images = arguments.white_images;
  options.no_white_image = arguments.no_white_image;
  options.grid = arguments.grid;
  options.plain = ToPlainRawOptions(arguments.plain);
  options.decode.demosaic = decode::DemosaicMethodFromString(arguments.demosaic);
  options.decode.colour = decode::ColourModeFromString(arguments.colour);
  if (!arguments.white_balance.empty())
    options.decode.white_balance = decode::WhiteBalanceFromString(arguments.white_balance);
  options.decode.correct_hot_pixels = !arguments.no_hot_pixels;
  if (!(arguments.dehex >= 0.0 && arguments.dehex <= 0.25)) throw Error(OptionName("dehex") + " must be in [0, 0.25]");
  options.decode.dehex = arguments.dehex;
  options.decode.flatten_lattice = !arguments.no_lattice_flattening;
  options.decode.flatten_jpeg_blocks = !arguments.no_jpeg_block_flattening;
  options.decode.central_views = arguments.views;
  return options;
}

nlohmann::json DecodeParameters(const DecodeArguments& arguments) {
  return {{"grid", arguments.grid.empty() ? nlohmann::json(nullptr) : nlohmann::json(arguments.grid)},
          {"demosaic", arguments.demosaic},
          {"colour", arguments.colour},
          {"white_balance",
           arguments.white_balance.empty() ? nlohmann::json(nullptr) : nlohmann::json(arguments.white_balance)},
          {"hot_pixels", !arguments.no_hot_pixels},
          {"dehex", arguments.dehex},
          {"lattice_flattening", !arguments.no_lattice_flattening},
          {"jpeg_block_flattening", !arguments.no_jpeg_block_flattening},
          {"views", arguments.views}};
}

}  // namespace lfsp::cli
