#pragma once

#include <cstdint>
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

// A file's size and modification time: what tells that a white image is still the one a database entry measured.
struct FileStamp {
  std::uintmax_t bytes = 0;
  std::int64_t modified_ns = 0;  // the file clock's nanoseconds
  bool operator==(const FileStamp&) const = default;
};
// The stamp of `path` now; none when it cannot be read.
std::optional<FileStamp> StampOf(const std::filesystem::path& path);

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
  // raw_path's and metadata_path's stamps when the entry was indexed (none in databases written before they were
  // kept). Only while both files still carry them is the entry reused instead of measured again, or its grid used.
  std::optional<FileStamp> raw_stamp;
  std::optional<FileStamp> metadata_stamp;
  // The lattice FitWhiteImageGrids fitted on this white image, exactly as a decode fits it (FitGridOnWhiteImage); a
  // decode that picks this white image, still as indexed, uses it instead of fitting again. None when not fitted: a
  // database built without `lfsp whites build`, a dark frame, a white image without a micro-lens description, a fit
  // that failed.
  std::optional<LensletGrid> grid;
};

// Whether the entry's files still carry the stamps it was indexed with (false when it has none).
bool StillAsIndexed(const WhiteImageEntry& entry);

struct WhiteImageDatabase {
  std::filesystem::path root;
  std::vector<WhiteImageEntry> entries;  // sorted by serial, zoom, focus, exposure, name
  std::vector<std::string> skipped;      // "<file>: <why>" for every MOD_* file that could not be indexed
};

// Mean normalised level below which a white image is treated as a dark frame (LFToolbox drops 12-bit means < 500).
inline constexpr double kDarkMeanLevel = 0.1;

// Indexes every MOD_*.TXT with its .RAW under `dir` (recursively; symbolic links to folders are not followed) and
// every calibration archive (a file starting with the LFP magic whose table of contents lists files[]). Each raw
// image is read once to check its size and measure its mean level. Unreadable pairs are listed in `skipped`, not
// fatal; a folder with no white image at all is an lfsp::Error.
WhiteImageDatabase BuildWhiteImageDatabase(const std::filesystem::path& dir);

// Fits the lenslet grid of every white image that is not dark and carries its micro-lens description
// (FitGridOnWhiteImage, as DecodeCaptureFile fits it), one white image at a time. A white image whose fit fails keeps
// no grid and is named in a warning. Returns how many grids were fitted. 0.5-1 s per full-size Illum white image.
int FitWhiteImageGrids(WhiteImageDatabase& database);

// What the stored grids were fitted with. Bump it whenever the grid a decode fits on an unchanged white image could
// come out different: FitGridOnWhiteImage and what it calls (EstimateLensletGrid and GridEstimateOptions' defaults,
// WhiteImageToGrey, GuessFromMetadata), how the white image and its metadata are read (raw unpacking, levels, the
// micro-lens description), or LensletGrid's fields and their JSON. A database whose grids carry another revision has
// them ignored (a decode fits again). tests/decode/white_grid_store_test.cc pins one fitted grid to catch a change.
inline constexpr int kWhiteGridFitRevision = 1;

// The JSON cache, written atomically (paths stored relative to the database file's folder). Stamps and grids are a
// cache: one that is malformed, or a grid that does not fit its entry's sensor, is left out with a warning naming the
// file and the entry; grids are read only when the file's grid_fit_revision is kWhiteGridFitRevision.
nlohmann::json WhiteImageDatabaseJson(const WhiteImageDatabase& database, const std::filesystem::path& base);
void WriteWhiteImageDatabase(const WhiteImageDatabase& database, const std::filesystem::path& path);
WhiteImageDatabase ReadWhiteImageDatabase(const std::filesystem::path& path);

// The database file name inside a white-image folder.
inline constexpr const char* kWhiteDatabaseFileName = "whites.json";

// Loads `dir`/whites.json when it exists and is newer than every MOD_*/data.C.* file in `dir`. Otherwise builds
// the database (and does not write it: reading must not modify the input folder), reusing the entries, and the grids,
// of any whites.json met under `dir` for the pairs whose files still carry the stamps recorded there (so the whites/
// folder beside the captures, once indexed, is not read again); every other pair is measured.
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
