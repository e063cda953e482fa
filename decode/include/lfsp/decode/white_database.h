#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/lytro_metadata.h"
#include "lfsp/decode/raw_packing.h"

namespace lfsp::decode {

// The white-image database of issue 4 (like LFToolbox's LFUtilProcessWhiteImages + LFSelectFromDatabase): an index
// of a camera's white ("modulation") images by serial, zoom step, focus step and exposure, built from MOD_####.RAW +
// .TXT pairs and/or calibration archives data.C.N, cached as JSON, with the lenslet grid fitted on each white image
// when `lfsp whites build` fitted it (so that decoding many captures fits each grid once, issue 46).

struct WhiteImageEntry {
  // Where the raw image lives: a .RAW file, or a member of a calibration archive.
  std::filesystem::path raw_path;       // MOD_0000.RAW, or the archive holding `raw_member`
  std::filesystem::path metadata_path;  // MOD_0000.TXT, or the archive holding `metadata_member`
  std::string raw_member;               // archives only: e.g. "C:\\T1CALIB\\MOD_0000.RAW"
  std::string metadata_member;

  std::string name;  // "MOD_0000" (for messages)
  std::string serial;
  std::string camera_model;
  int zoom_step = 0;
  int focus_step = 0;
  double exposure_duration = 0.0;  // s
  int width = 0;
  int height = 0;
  RawPacking packing = RawPacking::kBits10Illum;
  double mean_level = 0.0;  // mean of (raw - black) / (white - black) over the image
  bool dark = false;        // a dark frame (tagged darkFrame, or mean level < kDarkMeanLevel): never selected
  // The lattice FitWhiteImageGrids fitted on this white image, exactly as a decode would fit it; a decode that picks
  // this white image uses it instead of fitting again. None when not fitted: a database built on the fly by a decode,
  // a dark frame, a white image without a micro-lens description, a fit that failed.
  std::optional<LensletGrid> grid;
};

struct WhiteImageDatabase {
  std::filesystem::path root;
  std::vector<WhiteImageEntry> entries;  // sorted by serial, zoom, focus, exposure, name
  std::vector<std::string> skipped;      // "<file>: <why>" for every MOD_* file that could not be indexed
};

// Mean normalised level below which a white image is treated as a dark frame (LFToolbox drops 12-bit means < 500).
inline constexpr double kDarkMeanLevel = 0.1;

// Indexes every MOD_*.TXT with its .RAW under `dir` (recursively) and every calibration archive (a file starting
// with the LFP magic whose table of contents lists files[]). Each raw image is read once to check its size and
// measure its mean level. Unreadable pairs are listed in `skipped`, not fatal; a folder with no white image at
// all is an lfsp::Error.
WhiteImageDatabase BuildWhiteImageDatabase(const std::filesystem::path& dir);

// Fits the lenslet grid of every white image that is not dark and carries its micro-lens description
// (EstimateLensletGrid on WhiteImageToGrey, from GuessFromMetadata of its own metadata: what DecodeCaptureFile does
// with it), one white image at a time. A white image whose fit fails keeps no grid and is named in a warning. Returns
// how many grids were fitted. About 0.5 s per full-size Illum white image.
int FitWhiteImageGrids(WhiteImageDatabase& database);

// What the stored grids were fitted with. Bump it whenever EstimateLensletGrid, WhiteImageToGrey or
// GuessFromMetadata change what they return for the same white image: a database whose grids carry another revision
// has them ignored (and a decode fits again), so a stale grid is never used.
inline constexpr int kWhiteGridFitRevision = 1;

// The JSON cache, written atomically (paths stored relative to the database file's folder). Grids are read only
// when the file's grid_fit_revision is kWhiteGridFitRevision; a grid that is malformed or not for its entry's
// sensor is an lfsp::Error naming the file and the entry.
nlohmann::json WhiteImageDatabaseJson(const WhiteImageDatabase& database, const std::filesystem::path& base);
void WriteWhiteImageDatabase(const WhiteImageDatabase& database, const std::filesystem::path& path);
WhiteImageDatabase ReadWhiteImageDatabase(const std::filesystem::path& path);

// The database file name inside a white-image folder.
inline constexpr const char* kWhiteDatabaseFileName = "whites.json";

// Loads `dir`/whites.json when it exists and is newer than every MOD_*/data.C.* file in `dir`, otherwise builds
// the database (and does not write it: reading must not modify the input folder).
WhiteImageDatabase LoadOrBuildWhiteImageDatabase(const std::filesystem::path& dir);

struct WhiteImageChoice {
  const WhiteImageEntry* entry = nullptr;
  std::string explanation;  // which one and why, in one sentence
};

// Picks the white image for a capture: same camera serial, then nearest zoom step, then nearest focus step, then
// the longest exposure (F01 sets hold two exposures per step), then the name. Dark frames are never chosen.
// Throws lfsp::Error (naming the capture's serial and the serials present) when no white image matches.
WhiteImageChoice SelectWhiteImage(const WhiteImageDatabase& database, const LytroMetadata& capture);

// The unpacked raw image and metadata of an entry (from its .RAW/.TXT files or its archive).
RawImage ReadWhiteImageRaw(const WhiteImageEntry& entry);
LytroMetadata ReadWhiteImageMetadata(const WhiteImageEntry& entry);

}  // namespace lfsp::decode
