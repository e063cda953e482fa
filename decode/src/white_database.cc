#include "lfsp/decode/white_database.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"
#include "lfsp/core/json_fields.h"
#include "lfsp/core/parallel_for.h"
#include "lfsp/core/untrusted_json.h"
#include "lfsp/core/utf8.h"
#include "lfsp/decode/given_grid.h"
#include "lfsp/decode/lfp_container.h"
#include "lfsp/decode/lytro_capture.h"

namespace lfsp::decode {
namespace {

namespace fs = std::filesystem;

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

bool IsModMetadata(const fs::path& path) {
  const std::string name = Lower(path.filename().string());
  return name.rfind("mod_", 0) == 0 && (Lower(path.extension().string()) == ".txt");
}

bool IsArchive(const fs::path& path) { return Lower(path.filename().string()).rfind("data.c.", 0) == 0; }

// Whether `dir`/whites.json exists and is newer than every MOD_*, .RAW and data.C.* file under `dir`.
bool HasFreshDatabase(const fs::path& dir) {
  const fs::path cache = dir / kWhiteDatabaseFileName;
  std::error_code ec;
  if (!fs::is_regular_file(cache, ec)) return false;
  const auto cache_time = fs::last_write_time(cache, ec);
  if (ec) return false;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_regular_file(ec) &&
        (IsModMetadata(it->path()) || IsArchive(it->path()) || Lower(it->path().extension().string()) == ".raw")) {
      if (fs::last_write_time(it->path(), ec) > cache_time) return false;
    }
  }
  return !ec;
}

// The base name of an archived member: "C:\T1CALIB\MOD_0000.RAW" -> "MOD_0000.RAW".
std::string MemberBaseName(const std::string& member) {
  const std::size_t cut = member.find_last_of("\\/");
  return cut == std::string::npos ? member : member.substr(cut + 1);
}

std::string StemOf(const std::string& file_name) {
  const std::size_t dot = file_name.rfind('.');
  return dot == std::string::npos ? file_name : file_name.substr(0, dot);
}

// The mean of (level - black) / (white - black) over `pixels` pixels whose levels add up to `sum`.
double MeanLevel(double sum, std::size_t pixels, const RawFormat& format) {
  const double black = format.black.gr;
  const double range = format.white.gr - format.black.gr;
  return pixels == 0 ? 0.0 : (sum / static_cast<double>(pixels) - black) / range;
}

double MeanLevel(const RawImage& raw, const RawFormat& format) {
  double sum = 0.0;
  for (const std::uint16_t v : raw.pixels) sum += v;
  return MeanLevel(sum, raw.pixels.size(), format);
}

// The mean level of a MOD_####.RAW read a block at a time (SumPackedLevels), with the checks and the number of
// unpacking it whole: the database is built on every decode of a folder without whites.json, and unpacking its
// six full-size Illum whites (83 MB each) for one number each was 1.5 s of a loaded pipeline. The integer sum is
// exact in a double (below 2^53), so it equals MeanLevel's sum over the unpacked image.
double MeanLevelOfRawFile(const WhiteImageEntry& e, const RawFormat& format) {
  const std::string source = e.raw_path.string();
  if (e.width <= 0 || e.height <= 0)
    throw Error(source + ": raw image size " + std::to_string(e.width) + "x" + std::to_string(e.height) +
                " is not positive");
  RequireRegularFile(e.raw_path);
  const std::size_t pixels = static_cast<std::size_t>(e.width) * static_cast<std::size_t>(e.height);
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(e.raw_path, ec);
  if (ec) throw Error(source + ": cannot determine the file size");
  const std::size_t expected = PackedByteCount(e.packing, pixels);
  if (bytes != expected)
    throw Error(source + ": raw buffer of " + std::to_string(bytes) + " bytes, expected " + std::to_string(expected) +
                " bytes for " + std::to_string(pixels) + " pixels packed as " + std::string(ToString(e.packing)));
  std::ifstream in(e.raw_path, std::ios::binary);
  if (!in) throw Error(source + ": cannot open for reading");
  return MeanLevel(static_cast<double>(SumPackedLevels(e.packing, in, pixels, source)), pixels, format);
}

// Fills the metadata part of an entry; throws lfsp::Error naming the file if a needed field is missing.
WhiteImageEntry EntryFromMetadata(const LytroMetadata& md, const std::string& where) {
  WhiteImageEntry e;
  e.serial = md.serial;
  e.camera_model = md.camera_model;
  e.zoom_step = md.RequireZoomStep();
  e.focus_step = md.RequireFocusStep();
  if (!md.exposure_duration) throw Error(where + ": metadata field devices.shutter.frameExposureDuration is missing");
  e.exposure_duration = *md.exposure_duration;
  const RawFormat& format = md.RequireRawFormat();
  e.width = format.width;
  e.height = format.height;
  e.packing = format.packing;
  e.dark = md.dark_frame;
  return e;
}

void SetMeanLevel(WhiteImageEntry& e, double mean_level) {
  e.mean_level = mean_level;
  if (e.mean_level < kDarkMeanLevel) e.dark = true;
}

const std::vector<std::uint8_t>* FindMember(const LytroCapture& archive, const std::string& member) {
  for (const EmbeddedItem& item : archive.items) {
    if (item.kind == ItemKind::kCalibrationFile && item.name == member && item.present()) {
      return &archive.container.sections[static_cast<std::size_t>(item.section)].payload;
    }
  }
  return nullptr;
}

std::string_view AsText(const std::vector<std::uint8_t>& bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

// One MOD_####.TXT + .RAW pair: its entry, or why it was skipped.
struct IndexedPair {
  std::optional<WhiteImageEntry> entry;
  std::string skipped;
};

// Entries of databases met while indexing, by their raw file (and member): reused while their files are unchanged.
using StoredEntries = std::map<std::string, WhiteImageEntry>;

std::string EntryKey(const fs::path& raw_path, const std::string& member) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(raw_path, ec);
  return (ec ? raw_path.lexically_normal() : canonical).string() + '\n' + member;
}

// The entry a database met under the folder holds for this pair, if it measured these very files.
std::optional<WhiteImageEntry> Reusable(const StoredEntries* stored, const fs::path& raw, const fs::path& txt) {
  if (stored == nullptr) return std::nullopt;
  const auto found = stored->find(EntryKey(raw, ""));
  if (found == stored->end() || EntryKey(found->second.metadata_path, "") != EntryKey(txt, "") ||
      !StillAsIndexed(found->second))
    return std::nullopt;
  WhiteImageEntry e = found->second;
  e.raw_path = raw;
  e.metadata_path = txt;
  return e;
}

IndexedPair IndexPair(const fs::path& txt, const StoredEntries* stored) {
  fs::path raw;
  for (const char* ext : {".RAW", ".raw"}) {
    fs::path candidate = txt;
    candidate.replace_extension(ext);
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) raw = candidate;
  }
  if (raw.empty()) return {std::nullopt, txt.string() + ": no .RAW beside it"};
  if (std::optional<WhiteImageEntry> reused = Reusable(stored, raw, txt)) return {std::move(reused), {}};
  try {
    // Stamped before reading: a file that changes while it is read is not taken for the one measured.
    const std::optional<FileStamp> raw_stamp = StampOf(raw), metadata_stamp = StampOf(txt);
    const LytroMetadata md = ReadMetadataFile(txt);
    WhiteImageEntry e = EntryFromMetadata(md, txt.string());
    e.raw_path = raw;
    e.metadata_path = txt;
    e.name = txt.stem().string();
    SetMeanLevel(e, MeanLevelOfRawFile(e, md.RequireRawFormat()));
    e.raw_stamp = raw_stamp;
    e.metadata_stamp = metadata_stamp;
    return {std::move(e), {}};
  } catch (const Error& error) {
    return {std::nullopt, error.what()};
  }
}

// Every pair, read and measured in parallel (each white RAW is streamed for its mean level; the six full-size Illum
// whites of a simulated set took 0.51 s one after another unpacked whole, 0.38-0.45 s in parallel), then added in
// the pairs' order.
void IndexPairs(const std::vector<fs::path>& pairs, const StoredEntries* stored, WhiteImageDatabase& db) {
  std::vector<IndexedPair> indexed(pairs.size());
  // Anything but lfsp::Error (which skips the pair) is rethrown as it was once every pair is done.
  ParallelFor(static_cast<int>(pairs.size()), [&](int i) {
    indexed[static_cast<std::size_t>(i)] = IndexPair(pairs[static_cast<std::size_t>(i)], stored);
  });
  for (IndexedPair& pair : indexed) {
    if (pair.entry)
      db.entries.push_back(std::move(*pair.entry));
    else
      db.skipped.push_back(std::move(pair.skipped));
  }
}

// Calibration archives: members MOD_####.TXT and MOD_####.RAW, possibly in different volumes.
void IndexArchives(const std::vector<fs::path>& archives, WhiteImageDatabase& db) {
  struct Member {
    fs::path archive;
    std::string name;
  };
  std::map<std::string, Member> raws;  // base name -> where
  std::vector<std::pair<Member, std::string>> texts;
  for (const fs::path& path : archives) {
    try {
      const LytroCapture archive = OpenLytroCapture(path);
      for (const EmbeddedItem* item : archive.ItemsOf(ItemKind::kCalibrationFile)) {
        const std::string base = MemberBaseName(item->name);
        const std::string lower = Lower(base);
        if (lower.rfind("mod_", 0) != 0 || !item->present()) continue;
        if (lower.size() > 4 && lower.substr(lower.size() - 4) == ".raw")
          raws[Lower(StemOf(base))] = {path, item->name};
        if (lower.size() > 4 && lower.substr(lower.size() - 4) == ".txt") {
          texts.push_back(
              {{path, item->name},
               std::string(AsText(archive.container.sections[static_cast<std::size_t>(item->section)].payload))});
        }
      }
    } catch (const Error& error) {
      db.skipped.push_back(error.what());
    }
  }
  // Entries whose raw member sits in the same volume are measured one after the other, so each volume is opened
  // (and SHA-1 verified) once.
  std::stable_sort(texts.begin(), texts.end(), [&raws](const auto& a, const auto& b) {
    const auto ra = raws.find(Lower(StemOf(MemberBaseName(a.first.name))));
    const auto rb = raws.find(Lower(StemOf(MemberBaseName(b.first.name))));
    const fs::path pa = ra == raws.end() ? fs::path() : ra->second.archive;
    const fs::path pb = rb == raws.end() ? fs::path() : rb->second.archive;
    return pa < pb;
  });
  fs::path open_path;
  std::optional<LytroCapture> open_archive;
  for (const auto& [member, text] : texts) {
    const std::string where = member.archive.string() + " " + member.name;
    const std::string stem = StemOf(MemberBaseName(member.name));
    const auto raw = raws.find(Lower(stem));
    if (raw == raws.end()) {
      db.skipped.push_back(where + ": no MOD .RAW member of the same name in the archives");
      continue;
    }
    try {
      const LytroMetadata md = ParseMetadataDocument(text, where);
      WhiteImageEntry e = EntryFromMetadata(md, where);
      e.metadata_path = member.archive;
      e.metadata_member = member.name;
      e.raw_path = raw->second.archive;
      e.raw_member = raw->second.name;
      e.name = stem;
      e.raw_stamp = StampOf(e.raw_path);
      e.metadata_stamp = StampOf(e.metadata_path);
      if (!open_archive || open_path != e.raw_path) {
        open_archive.reset();  // release the previous volume before reading the next
        open_archive = OpenLytroCapture(e.raw_path);
        open_path = e.raw_path;
      }
      const std::vector<std::uint8_t>* bytes = FindMember(*open_archive, e.raw_member);
      if (bytes == nullptr) throw Error(where + ": raw member " + e.raw_member + " vanished");
      SetMeanLevel(
          e, MeanLevel(UnpackRawImage(e.packing, *bytes, e.width, e.height, e.raw_path.string() + " " + e.raw_member),
                       md.RequireRawFormat()));
      db.entries.push_back(std::move(e));
    } catch (const Error& error) {
      db.skipped.push_back(error.what());
    }
  }
}

void SortEntries(std::vector<WhiteImageEntry>& entries) {
  std::sort(entries.begin(), entries.end(), [](const WhiteImageEntry& a, const WhiteImageEntry& b) {
    return std::tie(a.serial, a.zoom_step, a.focus_step, a.exposure_duration, a.name) <
           std::tie(b.serial, b.zoom_step, b.focus_step, b.exposure_duration, b.name);
  });
}

// What a folder holds, found recursively (symbolic links to folders are not followed, so a link loop ends).
struct FolderContents {
  std::vector<fs::path> pairs;      // MOD_*.TXT
  std::vector<fs::path> archives;   // data.C.*
  std::vector<fs::path> databases;  // whites.json
};

FolderContents ScanFolder(const fs::path& dir) {
  FolderContents found;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    if (IsModMetadata(it->path())) found.pairs.push_back(it->path());
    if (IsArchive(it->path())) found.archives.push_back(it->path());
    if (it->path().filename() == kWhiteDatabaseFileName) found.databases.push_back(it->path());
  }
  std::sort(found.pairs.begin(), found.pairs.end());
  std::sort(found.archives.begin(), found.archives.end());
  std::sort(found.databases.begin(), found.databases.end());
  return found;
}

// The stamped entries of the databases found: only a cache, so one that cannot be read is named in a warning and
// left out.
StoredEntries ReadStoredEntries(const std::vector<fs::path>& databases) {
  StoredEntries stored;
  for (const fs::path& path : databases) {
    try {
      for (WhiteImageEntry& e : ReadWhiteImageDatabase(path).entries) {
        if (e.raw_member.empty() && e.raw_stamp && e.metadata_stamp)
          stored.emplace(EntryKey(e.raw_path, ""), std::move(e));
      }
    } catch (const Error& error) {
      spdlog::warn("{}; its white images are measured again (lfsp whites build rewrites it)", error.what());
    }
  }
  return stored;
}

// The database of `dir`; with `reuse`, pairs that a whites.json under `dir` measured in their present state are taken
// from it rather than measured again.
WhiteImageDatabase BuildDatabase(const fs::path& dir, bool reuse) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(dir.string() + ": not a folder of white images");
  WhiteImageDatabase db;
  db.root = dir;
  const FolderContents found = ScanFolder(dir);
  const StoredEntries stored = reuse ? ReadStoredEntries(found.databases) : StoredEntries{};
  IndexPairs(found.pairs, reuse ? &stored : nullptr, db);
  IndexArchives(found.archives, db);
  // whites.json keeps names as UTF-8 text: a white image whose file name is not (which made `whites build` an internal
  // failure) is left out with a reason.
  std::erase_if(db.entries, [&](const WhiteImageEntry& e) {
    for (const fs::path& path : {e.raw_path, e.metadata_path}) {
      if (FirstNonUtf8Byte(path.lexically_relative(dir).string()) == std::string::npos) continue;
      db.skipped.push_back(path.string() + ": the file name is not UTF-8 text, which whites.json cannot hold");
      return true;
    }
    return false;
  });
  // The reasons quote paths: in a folder whose own name is not UTF-8, they are written with \xHH escapes.
  for (std::string& reason : db.skipped) reason = PrintableText(reason);
  if (db.entries.empty()) {
    std::string why = dir.string() + ": no white image found (looked for MOD_*.TXT + .RAW pairs and data.C.* archives)";
    if (!db.skipped.empty()) why += "; first problem: " + db.skipped.front();
    throw Error(why);
  }
  SortEntries(db.entries);
  return db;
}

fs::path Relative(const fs::path& path, const fs::path& base) {
  if (path.empty()) return path;
  std::error_code ec;
  const fs::path relative = fs::relative(path, base, ec);
  return ec || relative.empty() ? path : relative;
}

std::string Format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

nlohmann::json StampJson(const FileStamp& stamp) {
  return {{"bytes", stamp.bytes}, {"modified_ns", stamp.modified_ns}};
}

FileStamp StampFromJson(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object() || !j.contains("bytes") || !j["bytes"].is_number_unsigned() || !j.contains("modified_ns") ||
      !j["modified_ns"].is_number_integer())
    throw Error(where + ": not a file stamp (bytes, modified_ns)");
  return {j["bytes"].get<std::uintmax_t>(), j["modified_ns"].get<std::int64_t>()};
}

// An entry's stamps and grid, which only spare work: one that is malformed, or a grid that does not lie on the entry's
// sensor, is left out with a warning rather than making the whole database unusable.
void ReadCachedFields(const nlohmann::json& j, const std::string& where, bool grids_current, WhiteImageEntry& e) {
  try {
    if (j.contains("raw_stamp")) e.raw_stamp = StampFromJson(j["raw_stamp"], where + " raw_stamp");
    if (j.contains("metadata_stamp")) e.metadata_stamp = StampFromJson(j["metadata_stamp"], where + " metadata_stamp");
  } catch (const Error& error) {
    spdlog::warn("{}; the entry is measured again where it is reused", error.what());
    e.raw_stamp.reset();
    e.metadata_stamp.reset();
  }
  if (!j.contains("grid") || !grids_current) return;
  try {
    LensletGrid grid = LensletGrid::FromJson(j["grid"], where + " grid");
    RequireGridOnSensor(grid, e.width, e.height, where + " grid");
    e.grid = grid;
  } catch (const Error& error) {
    spdlog::warn("{}; the grid is fitted again", error.what());
  }
}

}  // namespace

std::optional<FileStamp> StampOf(const fs::path& path) {
  std::error_code ec;
  FileStamp stamp;
  stamp.bytes = fs::file_size(path, ec);
  if (ec) return std::nullopt;
  const fs::file_time_type modified = fs::last_write_time(path, ec);
  if (ec) return std::nullopt;
  stamp.modified_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(modified.time_since_epoch()).count();
  return stamp;
}

bool StillAsIndexed(const WhiteImageEntry& e) {
  return e.raw_stamp && e.metadata_stamp && StampOf(e.raw_path) == e.raw_stamp &&
         StampOf(e.metadata_path) == e.metadata_stamp;
}

WhiteImageDatabase BuildWhiteImageDatabase(const fs::path& dir) { return BuildDatabase(dir, false); }

int FitWhiteImageGrids(WhiteImageDatabase& db) {
  int fitted = 0;
  for (WhiteImageEntry& e : db.entries) {
    e.grid.reset();
    if (e.dark) continue;
    try {
      const LytroMetadata metadata = ReadWhiteImageMetadata(e);
      if (!metadata.mla) continue;  // a decode would fit it from the capture's description: nothing to store
      const RawImage raw = ReadWhiteImageRaw(e);
      e.grid = FitGridOnWhiteImage(WhiteImageToGrey(raw, metadata.RequireRawFormat(), metadata.source), metadata).grid;
      ++fitted;
    } catch (const Error& error) {
      spdlog::warn("{}: no lenslet grid stored ({})", e.raw_path.string(), error.what());
    }
  }
  return fitted;
}

nlohmann::json WhiteImageDatabaseJson(const WhiteImageDatabase& db, const fs::path& base) {
  nlohmann::json entries = nlohmann::json::array();
  for (const WhiteImageEntry& e : db.entries) {
    nlohmann::json j = {{"name", e.name},
                        {"raw", Relative(e.raw_path, base).generic_string()},
                        {"metadata", Relative(e.metadata_path, base).generic_string()},
                        {"serial", e.serial},
                        {"camera_model", e.camera_model},
                        {"zoom_step", e.zoom_step},
                        {"focus_step", e.focus_step},
                        {"exposure_s", e.exposure_duration},
                        {"width", e.width},
                        {"height", e.height},
                        {"bits_per_pixel", BitsPerPixel(e.packing)},
                        {"mean_level", e.mean_level},
                        {"dark", e.dark}};
    if (!e.raw_member.empty()) j["raw_member"] = e.raw_member;
    if (!e.metadata_member.empty()) j["metadata_member"] = e.metadata_member;
    if (e.raw_stamp) j["raw_stamp"] = StampJson(*e.raw_stamp);
    if (e.metadata_stamp) j["metadata_stamp"] = StampJson(*e.metadata_stamp);
    if (e.grid) j["grid"] = e.grid->ToJson();
    entries.push_back(std::move(j));
  }
  return {{"lfsp_white_image_database", 1},
          {"grid_fit_revision", kWhiteGridFitRevision},
          {"entries", entries},
          {"skipped", db.skipped}};
}

void WriteWhiteImageDatabase(const WhiteImageDatabase& db, const fs::path& path) {
  const std::string text = WhiteImageDatabaseJson(db, path.parent_path()).dump(2);
  WriteFileBytesAtomic(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), path);
}

WhiteImageDatabase ReadWhiteImageDatabase(const fs::path& path) {
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path);
  const nlohmann::json doc = ParseUntrustedJson(AsText(bytes), path.string());
  // contains() before [] : on a const document, [] of a missing key is undefined (fuzz finding, white_folder: a
  // database with the marker and no entries read freed memory).
  if (!doc.is_object() || !doc.contains("lfsp_white_image_database") || !doc.contains("entries") ||
      !doc["entries"].is_array()) {
    throw Error(path.string() + ": not an lfsp white-image database (no lfsp_white_image_database / entries)");
  }
  WhiteImageDatabase db;
  db.root = path.parent_path();
  const fs::path base = path.parent_path();
  // Grids another revision of the fit made are not this one's: left out, so that a decode fits again.
  const bool grids_current =
      IntAt(doc, "grid_fit_revision", JsonSource(path.string())).value_or(0) == kWhiteGridFitRevision;
  for (std::size_t i = 0; i < doc["entries"].size(); ++i) {
    const nlohmann::json& j = doc["entries"][i];
    const std::string where = path.string() + " entry " + std::to_string(i);
    WhiteImageEntry e;
    e.name = RequireString(j, "name", where);
    e.raw_path = base / RequireString(j, "raw", where);
    e.metadata_path = base / RequireString(j, "metadata", where);
    e.raw_member = StringAt(j, "raw_member", where).value_or("");
    e.metadata_member = StringAt(j, "metadata_member", where).value_or("");
    e.serial = RequireString(j, "serial", where);
    e.camera_model = StringAt(j, "camera_model", where).value_or("");
    e.zoom_step = RequireInt(j, "zoom_step", where);
    e.focus_step = RequireInt(j, "focus_step", where);
    e.exposure_duration = RequireNumber(j, "exposure_s", where);
    e.width = RequireInt(j, "width", where);
    e.height = RequireInt(j, "height", where);
    const int bits = RequireInt(j, "bits_per_pixel", where);
    if (bits == 10) {
      e.packing = RawPacking::kBits10Illum;
    } else if (bits == 12) {
      e.packing = RawPacking::kBits12BigEndian;
    } else if (bits == 16) {
      e.packing = RawPacking::kBits16LittleEndian;
    } else {
      throw Error(where + ": bits_per_pixel " + std::to_string(bits) + " is not 10, 12 or 16");
    }
    e.mean_level = NumberAt(j, "mean_level", where).value_or(0.0);
    e.dark = BoolAt(j, "dark", where).value_or(false);
    ReadCachedFields(j, where, grids_current, e);
    db.entries.push_back(std::move(e));
  }
  if (doc.contains("skipped") && doc["skipped"].is_array()) {
    for (const auto& s : doc["skipped"]) {
      if (s.is_string()) db.skipped.push_back(s.get<std::string>());
    }
  }
  SortEntries(db.entries);
  return db;
}

WhiteImageDatabase LoadOrBuildWhiteImageDatabase(const fs::path& dir) {
  if (HasFreshDatabase(dir)) return ReadWhiteImageDatabase(dir / kWhiteDatabaseFileName);
  return BuildDatabase(dir, true);
}

WhiteImageChoice SelectWhiteImage(const WhiteImageDatabase& db, const LytroMetadata& capture) {
  const int zoom = capture.RequireZoomStep();
  const int focus = capture.RequireFocusStep();
  std::vector<const WhiteImageEntry*> candidates;
  std::vector<std::string> serials;
  std::size_t usable = 0;
  for (const WhiteImageEntry& e : db.entries) {
    if (e.dark) continue;
    ++usable;
    if (std::find(serials.begin(), serials.end(), e.serial) == serials.end()) serials.push_back(e.serial);
    if (capture.serial.empty() || e.serial == capture.serial) candidates.push_back(&e);
  }
  if (candidates.empty()) {
    std::string present;
    for (const std::string& s : serials) present += (present.empty() ? "" : ", ") + s;
    throw Error(capture.source + ": no white image for camera serial " + capture.serial + " in " + db.root.string() +
                " (" + std::to_string(usable) + " white images, serials: " + (present.empty() ? "none" : present) +
                ")");
  }
  const std::size_t serial_matches = candidates.size();
  const auto keep_nearest = [&candidates](auto distance) {
    int best = INT32_MAX;
    for (const WhiteImageEntry* e : candidates) best = std::min(best, distance(*e));
    std::erase_if(candidates, [&](const WhiteImageEntry* e) { return distance(*e) != best; });
    return best;
  };
  const int zoom_distance = keep_nearest([zoom](const WhiteImageEntry& e) { return std::abs(e.zoom_step - zoom); });
  const std::size_t at_zoom = candidates.size();
  const int focus_distance = keep_nearest([focus](const WhiteImageEntry& e) { return std::abs(e.focus_step - focus); });
  const std::size_t at_focus = candidates.size();
  std::sort(candidates.begin(), candidates.end(), [](const WhiteImageEntry* a, const WhiteImageEntry* b) {
    if (a->exposure_duration != b->exposure_duration) return a->exposure_duration > b->exposure_duration;
    return a->name < b->name;
  });
  const WhiteImageEntry& chosen = *candidates.front();
  std::ostringstream why;
  why << chosen.name << ": ";
  if (capture.serial.empty()) {
    why << "the capture has no serial number, so all " << serial_matches << " white images were considered; ";
  } else {
    why << "camera serial " << capture.serial << " (" << serial_matches << " of " << usable << " usable"
        << " white images); ";
  }
  why << "zoom step " << chosen.zoom_step << " nearest to the capture's " << zoom << " (off by " << zoom_distance
      << "); focus step " << chosen.focus_step << " nearest to " << focus << " among " << at_zoom
      << " at that zoom (off by " << focus_distance << ")";
  if (at_focus > 1) why << "; longest exposure (" << Format(chosen.exposure_duration) << " s) of " << at_focus;
  return {&chosen, why.str()};
}

LytroMetadata ReadWhiteImageMetadata(const WhiteImageEntry& entry) {
  if (entry.metadata_member.empty()) return ReadMetadataFile(entry.metadata_path);
  const LytroCapture archive = OpenLytroCapture(entry.metadata_path);
  const std::vector<std::uint8_t>* text = FindMember(archive, entry.metadata_member);
  if (text == nullptr) throw Error(entry.metadata_path.string() + ": no member " + entry.metadata_member);
  return ParseMetadataDocument(AsText(*text), entry.metadata_path.string() + " " + entry.metadata_member);
}

RawImage ReadWhiteImageRaw(const WhiteImageEntry& entry) {
  if (entry.raw_member.empty()) {
    const std::vector<std::uint8_t> bytes = ReadFileBytes(entry.raw_path);
    return UnpackRawImage(entry.packing, bytes, entry.width, entry.height, entry.raw_path.string());
  }
  const LytroCapture archive = OpenLytroCapture(entry.raw_path);
  const std::vector<std::uint8_t>* bytes = FindMember(archive, entry.raw_member);
  if (bytes == nullptr) throw Error(entry.raw_path.string() + ": no member " + entry.raw_member);
  return UnpackRawImage(entry.packing, *bytes, entry.width, entry.height,
                        entry.raw_path.string() + " " + entry.raw_member);
}

}  // namespace lfsp::decode
