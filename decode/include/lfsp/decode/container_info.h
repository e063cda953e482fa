#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lfsp::decode {

// `lfsp info` and `lfsp info --extract` for Lytro inputs (LFP/LFR containers, calibration archives, raw +
// metadata pairs, white-image TXT / frame JSON files).

// True when the file starts with the LFP magic, is named .lfp/.lfr (so a damaged one gets the reader's error), is a
// .RAW with a metadata partner, or is a .TXT/.json file that holds Lytro frame metadata. Cheap (reads at most the first
// bytes of a container); never throws.
bool LooksLikeLytroFile(const std::filesystem::path& path);

// Opens the file (verifying every SHA-1) and describes it: format and schema, every section (kind, offset,
// length, sha1, what it holds), the metadata summary (camera, serial, zoom/focus, exposure, raw format, MLA,
// colour), what the file holds (raw image, white image, depth maps, focus stack) and the references it lacks.
// Throws lfsp::Error naming the file on bad input.
nlohmann::ordered_json DescribeLytroFile(const std::filesystem::path& path);

// The description as readable text, one fact per line.
std::string FormatLytroDescription(const nlohmann::ordered_json& description);

// Writes the embedded items into `out_dir` (created if needed): JPEG frames (.jpg), H.264 blocks (.h264), depth
// / confidence maps and depth LUTs as PFM (core WritePfm), the table of contents and frame metadata as JSON,
// raw images and other binary payloads as .raw/.bin, calibration files under their archived names, plus
// manifest.json (the description and the list of files written). Everything is checked before the first file
// is written, and each file is written atomically. Returns the paths written.
std::vector<std::filesystem::path> ExtractLytroFile(const std::filesystem::path& path,
                                                    const std::filesystem::path& out_dir);

}  // namespace lfsp::decode
