#pragma once

// Which file of a views folder is which view. Folders written by other tools name their views in many ways; each
// is detected from the file names and said in one line, and `--views-pattern` covers the rest.
//
//   HCI            input_Cam%03d.png, camera = row * num_cams_x + column (0-based), size from parameters.cfg
//   <row>_<col>    [prefix]<row>_<col>.<ext>: the central 9x9 of an Illum decode as 3_3.png .. 11_11.png,
//                  view_1_1.png .. view_7_7.png, EPINET-style 2067_01_01.png; the first number is the row
//   LFToolbox      <name>_<index>_<a>_<b>.<ext> with index a permutation of 1..N (LFToolbox's export): a is the
//                  column, b the row
//   pattern        --views-pattern with {row} and {col} (and {index}, ignored) in place of the numbers
//
// Indices may start anywhere (0, 1, 3): the smallest row and column found become view 0. The angular size is the
// number of distinct rows and columns, and every combination must be present.

#include <filesystem>
#include <string>
#include <vector>

namespace lfsp {

struct ViewsLayout {
  std::string naming;  // "HCI input_Cam###", "<row>_<col>", "LFToolbox <index>_<column>_<row>", "--views-pattern '...'"
  int nu = 0;          // views per row (columns)
  int nv = 0;          // rows
  std::vector<std::filesystem::path> files;         // by camera number v * nu + u
  std::vector<std::filesystem::path> weight_files;  // HCI weight_Cam### by camera number, like files, else empty
  std::string description;                          // one line for the log: naming, index ranges, size
};

// The layout of the views in `folder`. `pattern` (from --views-pattern) overrides detection. Throws lfsp::Error
// naming the folder (or the first missing view) when no layout fits, and naming the folder and the first camera
// without a weight (or weight without a view) when HCI weight_Cam### files do not cover exactly the views' cameras.
ViewsLayout FindViewsLayout(const std::filesystem::path& folder, const std::string& pattern = "");

}  // namespace lfsp
