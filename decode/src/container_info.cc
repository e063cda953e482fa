#include "lfsp/decode/container_info.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/light_field.h"
#include "lfsp/core/pfm.h"
#include "lfsp/decode/lytro_capture.h"

namespace lfsp::decode {
namespace {

using ordered_json = nlohmann::ordered_json;

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

bool IsJpeg(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

template <typename T>
void PutOptional(ordered_json& out, const char* key, const std::optional<T>& value) {
  if (value) out[key] = *value;
}

ordered_json BayerJson(const BayerValues& v) { return {{"r", v.r}, {"gr", v.gr}, {"gb", v.gb}, {"b", v.b}}; }

ordered_json MetadataJson(const LytroMetadata& md) {
  ordered_json out;
  out["source"] = md.source;
  out["schema"] = md.schema;
  out["camera"] = {{"make", md.camera_make},
                   {"model", md.camera_model},
                   {"serial", md.serial},
                   {"sensor_serial", md.sensor_serial},
                   {"firmware", md.firmware}};
  ordered_json lens = ordered_json::object();
  PutOptional(lens, "zoom_step", md.zoom_step);
  PutOptional(lens, "focus_step", md.focus_step);
  PutOptional(lens, "f_number", md.f_number);
  PutOptional(lens, "focal_length_m", md.focal_length);
  out["lens"] = lens;
  ordered_json exposure = ordered_json::object();
  PutOptional(exposure, "duration_s", md.exposure_duration);
  PutOptional(exposure, "iso", md.iso);
  PutOptional(exposure, "modulation_exposure_bias", md.modulation_exposure_bias);
  PutOptional(exposure, "limit_exposure_bias", md.limit_exposure_bias);
  out["exposure"] = exposure;
  if (md.raw_format) {
    const RawFormat& f = *md.raw_format;
    out["raw_format"] = {{"width", f.width},
                         {"height", f.height},
                         {"packing", ToString(f.packing)},
                         {"bits_per_pixel", BitsPerPixel(f.packing)},
                         {"packed_bytes", PackedByteCount(f.packing, static_cast<std::size_t>(f.width) *
                                                                         static_cast<std::size_t>(f.height))},
                         {"mosaic", ToString(f.mosaic)},
                         {"black", BayerJson(f.black)},
                         {"white", BayerJson(f.white)}};
  } else {
    out["raw_format_problem"] = md.raw_format_problem;
  }
  if (md.mla) {
    const MlaDescription& m = *md.mla;
    out["mla"] = {{"lens_pitch_m", m.lens_pitch},
                  {"pixel_pitch_m", m.pixel_pitch},
                  {"spacing_px", m.ApproxSpacingPixels()},
                  {"rotation_rad", m.rotation},
                  {"scale_factor", {m.scale_x, m.scale_y}},
                  {"sensor_offset_m", {m.offset_x, m.offset_y, m.offset_z}},
                  {"tiling", m.tiling}};
  } else {
    out["mla_problem"] = md.mla_problem;
  }
  ordered_json colour = ordered_json::object();
  if (md.colour.ccm) colour["ccm"] = *md.colour.ccm;
  if (md.colour.white_balance_gain) colour["white_balance_gain"] = BayerJson(*md.colour.white_balance_gain);
  PutOptional(colour, "gamma", md.colour.gamma);
  if (md.colour.normalized_response) colour["normalized_response"] = BayerJson(*md.colour.normalized_response);
  if (md.colour.awb_gain) colour["awb_gain"] = BayerJson(*md.colour.awb_gain);
  PutOptional(colour, "awb_cct", md.colour.awb_cct);
  if (!md.colour.per_ccm.empty()) {
    ordered_json per = ordered_json::array();
    for (const auto& entry : md.colour.per_ccm) per.push_back({{"cct", entry.cct}, {"ccm", entry.ccm}});
    colour["per_ccm"] = per;
  }
  out["colour"] = colour;
  out["modulation_frame"] = md.modulation_frame;
  return out;
}

ordered_json ItemJson(const EmbeddedItem& item) {
  ordered_json out = {{"kind", ToString(item.kind)}, {"json_path", item.json_path}};
  if (!item.reference.empty()) out["reference"] = item.reference;
  out["present"] = item.present();
  if (item.present() && !item.reference.empty()) out["section"] = item.section;
  if (!item.name.empty()) out["name"] = item.name;
  if (item.width > 0) out["width"] = item.width;
  if (item.height > 0) out["height"] = item.height;
  if (!item.representation.empty()) out["representation"] = item.representation;
  return out;
}

std::string SizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

ordered_json HoldsJson(const LytroCapture& capture) {
  ordered_json holds;
  holds["raw_image"] = capture.HasRawImage() && !capture.IsWhiteImage();
  bool white = capture.IsWhiteImage() && capture.HasRawImage();
  for (const EmbeddedItem* item : capture.ItemsOf(ItemKind::kWhiteImage)) white = white || item->present();
  holds["white_image"] = white;
  ordered_json depth = ordered_json::array();
  for (const ItemKind kind : {ItemKind::kDepthMap, ItemKind::kConfidenceMap, ItemKind::kDepthLut}) {
    for (const EmbeddedItem* item : capture.ItemsOf(kind)) {
      if (item->present()) depth.push_back({{"kind", ToString(kind)}, {"size", SizeText(item->width, item->height)}});
    }
  }
  holds["depth_maps"] = depth;
  std::size_t frames = 0;
  std::map<std::string, std::size_t> by_representation;
  for (const ItemKind kind : {ItemKind::kFocusStackImage, ItemKind::kImageBlock}) {
    for (const EmbeddedItem* item : capture.ItemsOf(kind)) {
      if (!item->present()) continue;
      ++frames;
      ++by_representation[item->representation.empty() ? "unknown" : item->representation];
    }
  }
  holds["focus_stack"] = {{"items", frames}, {"by_representation", by_representation}};
  holds["summary"] = capture.HoldsSummary();
  return holds;
}

std::string FormatNumber(const ordered_json& value) {
  if (value.is_number_float()) {
    std::ostringstream out;
    out << value.get<double>();
    return out.str();
  }
  return value.is_string() ? value.get<std::string>() : value.dump();
}

// Section index -> what refers to it, for the section table.
std::map<std::size_t, std::string> SectionRoles(const LytroCapture& capture) {
  std::map<std::size_t, std::string> roles;
  const LfpSection* toc = capture.container.FindToc();
  for (std::size_t i = 0; i < capture.container.sections.size(); ++i) {
    if (&capture.container.sections[i] == toc) roles[i] = "table of contents";
  }
  for (const EmbeddedItem& item : capture.items) {
    if (!item.present() || item.reference.empty()) continue;
    std::string role(ToString(item.kind));
    if (!item.name.empty()) role += " (" + item.name + ")";
    std::string& slot = roles[static_cast<std::size_t>(item.section)];
    if (slot.empty()) slot = role;
  }
  return roles;
}

// A file name that cannot leave the output folder: archived names like "C:\T1CALIB\MOD_0000.RAW" become
// "T1CALIB__MOD_0000.RAW" (the LFToolbox convention); any other unsafe character becomes '_'.
std::string SafeName(std::string name) {
  if (name.size() >= 2 && name[1] == ':') name = name.substr(2);
  while (!name.empty() && (name.front() == '\\' || name.front() == '/')) name.erase(0, 1);
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (c == '\\' || c == '/') {
      out += "__";
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_') {
      out += c;
    } else {
      out += '_';
    }
  }
  if (out.empty() || out.find_first_not_of('.') == std::string::npos) out = "unnamed" + out;
  return out;
}

DisparityMap FloatMap(std::span<const std::uint8_t> payload, int width, int height, const std::string& what) {
  const std::size_t expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;
  if (payload.size() != expected) {
    throw Error(what + ": " + std::to_string(payload.size()) + " bytes, expected " + std::to_string(expected) +
                " for " + SizeText(width, height) + " float32 values");
  }
  DisparityMap map(width, height);
  // float32 little-endian (the only representation seen: "raw" / "packedFloat"); this host is little-endian.
  static_assert(sizeof(float) == 4);
  std::memcpy(map.data(), payload.data(), expected);
  return map;
}

constexpr const char* kManifestName = "manifest.json";

struct PlannedFile {
  std::string name;
  std::span<const std::uint8_t> bytes;  // written as is, unless `map` is set
  std::optional<DisparityMap> map;      // written as PFM
  std::string text;                     // written as text when bytes and map are empty
};

std::string Numbered(const std::string& stem, std::size_t n, const std::string& ext) {
  char buffer[16];
  std::snprintf(buffer, sizeof(buffer), "_%02zu", n);
  return stem + buffer + ext;
}

std::vector<PlannedFile> PlanExtraction(const LytroCapture& capture) {
  std::vector<PlannedFile> plan;
  const std::string source = capture.path.string();
  if (!capture.container.sections.empty()) plan.push_back({"table_of_contents.json", {}, {}, capture.toc.dump(2)});
  if (capture.format != "LFP container") plan.push_back({"metadata.json", {}, {}, capture.toc.dump(2)});
  if (capture.metadata) {
    plan.push_back({"frame_metadata.json", {}, {}, capture.metadata->frame_metadata.dump(2)});
    if (!capture.metadata->private_metadata.empty()) {
      plan.push_back({"private_metadata.json", {}, {}, capture.metadata->private_metadata.dump(2)});
    }
  }
  std::map<ItemKind, std::size_t> counters;
  // Each payload is extracted once, however many references name it: a table of contents that listed one frame
  // 100,000 times wrote 17 GB from a 1.6 MB file. So the payloads written add up to at most the input's size.
  std::set<int> extracted;  // section indices; kRawPairPayload for the .RAW of a raw + metadata pair
  constexpr int kRawPairPayload = -1;
  for (const EmbeddedItem& item : capture.items) {
    if (!item.present()) continue;
    if (item.kind == ItemKind::kFrameMetadata || item.kind == ItemKind::kPrivateMetadata)
      continue;  // written above as parsed JSON
    if (!extracted.insert(capture.raw_path.empty() ? item.section : kRawPairPayload).second) continue;
    const std::span<const std::uint8_t> payload =
        capture.raw_path.empty()
            ? std::span<const std::uint8_t>(capture.container.sections[static_cast<std::size_t>(item.section)].payload)
            : std::span<const std::uint8_t>(capture.raw_pair_bytes);
    const std::size_t n = counters[item.kind]++;
    const std::string what = source + " " + item.json_path;
    switch (item.kind) {
      case ItemKind::kFrameMetadata:
      case ItemKind::kPrivateMetadata:
        break;
      case ItemKind::kRawImage:
        plan.push_back({n ? Numbered("raw_image", n, ".raw") : "raw_image.raw", payload, {}, {}});
        break;
      case ItemKind::kWhiteImage:
        plan.push_back({n ? Numbered("white_image", n, ".raw") : "white_image.raw", payload, {}, {}});
        break;
      case ItemKind::kDepthMap:
      case ItemKind::kConfidenceMap:
      case ItemKind::kDepthLut: {
        const std::string stem = item.kind == ItemKind::kDepthMap        ? "depth_map"
                                 : item.kind == ItemKind::kConfidenceMap ? "confidence_map"
                                                                         : "depth_lut";
        if (item.width > 0 && item.height > 0) {
          plan.push_back({Numbered(stem, n, ".pfm"), {}, FloatMap(payload, item.width, item.height, what), {}});
        } else {
          plan.push_back({Numbered(stem, n, ".bin"), payload, {}, {}});
        }
        break;
      }
      case ItemKind::kFocusStackImage:
      case ItemKind::kThumbnail: {
        const std::string stem = item.kind == ItemKind::kThumbnail ? "thumbnail" : "focus_stack";
        plan.push_back({Numbered(stem, n, IsJpeg(payload) ? ".jpg" : ".bin"), payload, {}, {}});
        break;
      }
      case ItemKind::kImageBlock:
        plan.push_back(
            {Numbered("image_block", n, Lower(item.representation) == "h264" ? ".h264" : ".bin"), payload, {}, {}});
        break;
      case ItemKind::kCalibrationFile:
        plan.push_back(
            {item.name.empty() ? Numbered("calibration_file", n, ".bin") : SafeName(item.name), payload, {}, {}});
        break;
      case ItemKind::kOther: {
        std::string key = item.json_path.substr(item.json_path.rfind('.') + 1);
        plan.push_back({Numbered(SafeName(key), n, ".bin"), payload, {}, {}});
        break;
      }
    }
  }
  for (const std::size_t i : capture.UnreferencedSections()) {
    // An empty section holds nothing to extract (a container padded with 20,000 of them made 20,000 empty files).
    if (capture.container.sections[i].payload.empty()) continue;
    plan.push_back({Numbered("unreferenced_section", i, ".bin"), capture.container.sections[i].payload, {}, {}});
  }
  // Two archived names could collide after SafeName; number the duplicates rather than overwrite (the manifest
  // included, which is written last).
  std::map<std::string, int> seen = {{std::string(kManifestName), 1}};
  for (PlannedFile& file : plan) {
    if (seen[file.name]++ > 0) file.name = std::to_string(seen[file.name] - 1) + "_" + file.name;
  }
  return plan;
}

// Writes one file inside the extraction's temporary folder. No temporary of its own: the folder is swapped in whole
// (an AtomicOutput per file scanned the folder for stale temporaries, quadratic in the 20,000 files of a hostile
// container).
void WriteInto(std::span<const std::uint8_t> bytes, const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) ThrowFileError(path.string(), "write failed (disk full?)");
}

void WriteTextInto(const std::string& text, const std::filesystem::path& path) {
  WriteInto(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), path);
}

// The extraction replaces `out_dir` whole: only an empty folder or an earlier extraction (it has a manifest).
void CheckReplaceableExtractionFolder(const std::filesystem::path& out_dir) {
  std::error_code ec;
  if (!std::filesystem::exists(out_dir, ec)) return;
  if (!std::filesystem::is_directory(out_dir, ec))
    ThrowFileError(out_dir.string(), "exists and is not a folder; refusing to replace it");
  if (!std::filesystem::is_empty(out_dir, ec) && !std::filesystem::exists(out_dir / kManifestName, ec))
    ThrowFileError(out_dir.string(),
                   "exists, is not empty and holds no earlier extraction (no manifest.json); "
                   "refusing to replace it");
}

}  // namespace

bool LooksLikeLytroFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  std::uint8_t head[12] = {};
  in.read(reinterpret_cast<char*>(head), sizeof(head));
  if (in.gcount() == sizeof(head) && HasLfpMagic(head)) return true;
  const std::string ext = Lower(path.extension().string());
  // A damaged container should still reach the container reader, whose error says what is wrong with it.
  if (ext == ".lfp" || ext == ".lfr") return true;
  if (ext == ".raw") return !FindMetadataPartner(path).empty();
  if (ext == ".txt" || ext == ".json") {
    // Frame metadata mentions these keys early; do not parse a large unrelated JSON file here.
    std::string text(4096, '\0');
    in.clear();
    in.seekg(0);
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text.find("\"frameArray\"") != std::string::npos || text.find("\"rawDetails\"") != std::string::npos ||
           text.find("\"lytro") != std::string::npos || text.find("schema.lytro.com") != std::string::npos ||
           (text.find("\"devices\"") != std::string::npos && text.find("\"image\"") != std::string::npos);
  }
  return false;
}

namespace {
ordered_json DescribeCapture(const LytroCapture& capture, const std::filesystem::path& path);
}  // namespace

nlohmann::ordered_json DescribeLytroFile(const std::filesystem::path& path) {
  return DescribeCapture(OpenLytroCapture(path), path);
}

namespace {

ordered_json DescribeCapture(const LytroCapture& capture, const std::filesystem::path& path) {
  ordered_json out;
  out["file"] = path.string();
  out["format"] = capture.format;
  out["schema"] = capture.schema;
  std::error_code ec;
  out["size_bytes"] = std::filesystem::file_size(capture.path, ec);
  if (!capture.raw_path.empty()) out["raw_file"] = capture.raw_path.string();
  if (!capture.container.sections.empty()) {
    out["section_counts"] = {{"LFM", capture.container.CountOf(SectionKind::kMetadata)},
                             {"LFC", capture.container.CountOf(SectionKind::kContent)},
                             {"total", capture.container.sections.size()}};
    const auto roles = SectionRoles(capture);
    ordered_json sections = ordered_json::array();
    for (std::size_t i = 0; i < capture.container.sections.size(); ++i) {
      const LfpSection& s = capture.container.sections[i];
      const auto role = roles.find(i);
      sections.push_back({{"index", i},
                          {"kind", ToString(s.kind)},
                          {"offset", s.offset},
                          {"length", s.payload.size()},
                          {"sha1", s.sha1},
                          {"sha1_verified", true},
                          {"holds", role == roles.end() ? "unreferenced" : role->second}});
    }
    out["sections"] = sections;
  }
  if (capture.metadata) {
    out["metadata"] = MetadataJson(*capture.metadata);
  } else {
    out["metadata_problem"] = capture.metadata_problem;
    // Desktop exports of F01 pictures drop the frame metadata, but only the F01 used the picture.frameArray
    // schema (Illum files use frames[]), so the camera is still known.
    if (capture.schema.rfind("F01", 0) == 0) {
      out["camera_inferred"] = {{"model", "F01"}, {"basis", "picture.frameArray schema (first-generation Lytro)"}};
    }
  }
  out["holds"] = HoldsJson(capture);
  ordered_json items = ordered_json::array();
  ordered_json missing = ordered_json::array();
  for (const EmbeddedItem& item : capture.items) {
    items.push_back(ItemJson(item));
    if (!item.present()) missing.push_back(item.json_path + " -> " + item.reference);
  }
  out["items"] = items;
  out["missing_references"] = missing;
  return out;
}

}  // namespace

std::string FormatLytroDescription(const nlohmann::ordered_json& d) {
  std::ostringstream out;
  out << d.value("file", "") << "\n";
  out << "  format       " << d.value("format", "") << ", " << d.value("schema", "") << "\n";
  out << "  size         " << d.value("size_bytes", 0) << " bytes\n";
  if (d.contains("raw_file")) out << "  raw file     " << d["raw_file"].get<std::string>() << "\n";
  if (d.contains("metadata")) {
    const auto& m = d["metadata"];
    const auto& cam = m["camera"];
    out << "  camera       " << cam.value("make", "") << " " << cam.value("model", "")
        << (cam.value("serial", "").empty() ? "" : ", serial " + cam.value("serial", "")) << "\n";
    std::string lens;
    for (const auto& [key, value] : m["lens"].items())
      lens += (lens.empty() ? "" : ", ") + key + " " + FormatNumber(value);
    out << "  lens         " << (lens.empty() ? "(no lens metadata)" : lens) << "\n";
    std::string exposure;
    for (const auto& [key, value] : m["exposure"].items()) {
      exposure += (exposure.empty() ? "" : ", ") + key + " " + FormatNumber(value);
    }
    out << "  exposure     " << (exposure.empty() ? "(no exposure metadata)" : exposure) << "\n";
    if (m.contains("raw_format")) {
      const auto& f = m["raw_format"];
      out << "  raw format   " << f["width"] << "x" << f["height"] << ", " << f["packing"].get<std::string>() << ", "
          << f["mosaic"].get<std::string>() << ", black " << FormatNumber(f["black"]["gr"]) << " / white "
          << FormatNumber(f["white"]["gr"]) << "\n";
    } else {
      out << "  raw format   unknown: " << m.value("raw_format_problem", "") << "\n";
    }
    if (m.contains("mla")) {
      const auto& mla = m["mla"];
      out << "  micro-lenses pitch " << FormatNumber(mla["lens_pitch_m"]) << " m (" << FormatNumber(mla["spacing_px"])
          << " px), rotation " << FormatNumber(mla["rotation_rad"]) << " rad, " << mla.value("tiling", "") << "\n";
    }
    if (m.value("modulation_frame", false)) out << "  white image  yes (modulation frame)\n";
  } else {
    if (d.contains("camera_inferred")) {
      out << "  camera       " << d["camera_inferred"].value("model", "") << " (inferred from the "
          << d["camera_inferred"].value("basis", "") << ")\n";
    }
    out << "  metadata     none: " << d.value("metadata_problem", "") << "\n";
  }
  const auto& holds = d["holds"];
  out << "  raw image    " << (holds.value("raw_image", false) ? "yes" : "no (cannot be decoded)") << "\n";
  out << "  holds        " << holds.value("summary", "") << "\n";
  if (d.contains("sections")) {
    const auto& counts = d["section_counts"];
    out << "  sections     " << counts["total"] << " (" << counts["LFM"] << " LFM, " << counts["LFC"]
        << " LFC), every SHA-1 verified\n";
    for (const auto& s : d["sections"]) {
      char line[256];
      std::snprintf(line, sizeof(line), "    %3d %s @%-9llu %10llu B  %s  %s\n", s["index"].get<int>(),
                    s["kind"].get<std::string>().c_str(),
                    static_cast<unsigned long long>(s["offset"].get<std::uint64_t>()),
                    static_cast<unsigned long long>(s["length"].get<std::uint64_t>()),
                    s["sha1"].get<std::string>().substr(0, 17).c_str(), s["holds"].get<std::string>().c_str());
      out << line;
    }
  }
  if (!d["missing_references"].empty()) {
    out << "  not in file  " << d["missing_references"].size() << " reference(s):\n";
    for (const auto& ref : d["missing_references"]) out << "    " << ref.get<std::string>() << "\n";
  }
  return out.str();
}

std::vector<std::filesystem::path> ExtractLytroFile(const std::filesystem::path& path,
                                                    const std::filesystem::path& out_dir) {
  const LytroCapture capture = OpenLytroCapture(path);
  const ordered_json description = DescribeCapture(capture, path);  // one read, one SHA-1 pass
  std::vector<PlannedFile> plan = PlanExtraction(capture);          // throws before anything is written
  CheckReplaceableExtractionFolder(out_dir);
  // Built under a temporary name and renamed into place when complete, as `pipeline` builds its folder.
  AtomicOutput folder(out_dir);
  std::error_code ec;
  std::filesystem::create_directory(folder.temporary(), ec);
  if (ec) ThrowFileError(out_dir.string(), "cannot create the output folder (" + ec.message() + ")");
  std::vector<std::filesystem::path> written;
  ordered_json files = ordered_json::array();
  for (const PlannedFile& file : plan) {
    const std::filesystem::path target = folder.temporary() / file.name;
    if (file.map) {
      WritePfm(*file.map, target);
    } else if (!file.bytes.empty()) {
      WriteInto(file.bytes, target);
    } else {
      WriteTextInto(file.text, target);
    }
    written.push_back(folder.destination() / file.name);
    files.push_back(file.name);
  }
  ordered_json manifest = {{"description", description}, {"files", files}};
  WriteTextInto(manifest.dump(2), folder.temporary() / kManifestName);
  written.push_back(folder.destination() / kManifestName);
  folder.Commit();
  return written;
}

}  // namespace lfsp::decode
