#include "lfsp/decode/lytro_capture.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "json_text.h"
#include "lfsp/core/error.h"
#include "lfsp/core/json_fields.h"

namespace lfsp::decode {
namespace {

bool EndsWith(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

// The first number / string named `key` in the innermost object of `ancestors` that has it.
int IntFromAncestors(const std::vector<const nlohmann::json*>& ancestors, const char* key) {
  for (auto it = ancestors.rbegin(); it != ancestors.rend(); ++it) {
    const auto found = (*it)->find(key);
    if (found != (*it)->end() && found->is_number()) {
      const double value = found->get<double>();
      if (value >= 0 && value < 1e6) return static_cast<int>(value);
      return 0;
    }
  }
  return 0;
}

std::string StringFromAncestors(const std::vector<const nlohmann::json*>& ancestors, const char* key) {
  for (auto it = ancestors.rbegin(); it != ancestors.rend(); ++it) {
    const auto found = (*it)->find(key);
    if (found != (*it)->end() && found->is_string()) return found->get<std::string>();
  }
  return "";
}

// Decides what a reference is from where it sits in the table of contents; both schemas (F01
// picture.frameArray / accelerationArray, Illum frames / accelerations) and calibration archives (files[]).
ItemKind Classify(const std::string& parent_path, const std::string& key) {
  if (key == "modulationDataRef") return ItemKind::kWhiteImage;
  if (key == "blockOfImagesRef") return ItemKind::kImageBlock;
  if (key == "dataRef" && parent_path.find("files[") != std::string::npos) return ItemKind::kCalibrationFile;
  if (EndsWith(parent_path, ".frame") || parent_path == "frame") {
    if (key == "imageRef") return ItemKind::kRawImage;
    if (key == "metadataRef") return ItemKind::kFrameMetadata;
    if (key == "privateMetadataRef") return ItemKind::kPrivateMetadata;
  }
  if (key == "imageRef") {
    if (EndsWith(parent_path, "depthLut")) return ItemKind::kDepthLut;
    if (EndsWith(parent_path, "depthMap")) return ItemKind::kDepthMap;
    if (EndsWith(parent_path, "confidenceMap")) return ItemKind::kConfidenceMap;
    if (parent_path.find("thumbnail") != std::string::npos) return ItemKind::kThumbnail;
    if (parent_path.find("imageArray[") != std::string::npos || parent_path.find("perImage[") != std::string::npos) {
      return ItemKind::kFocusStackImage;
    }
  }
  return ItemKind::kOther;
}

std::string FormatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

class ItemCollector {
 public:
  ItemCollector(const LfpContainer& container, bool modulation_frame, std::string source)
      : container_(container), modulation_frame_(modulation_frame), source_(std::move(source)) {}

  void Walk(const nlohmann::json& node, const std::string& path, int depth = 0) {
    // Real tables of contents are under 15 levels deep; a hostile one must not exhaust the stack.
    if (depth > kMaxDepth)
      throw Error(source_ + ": table of contents nested deeper than " + std::to_string(kMaxDepth) + " levels");
    if (node.is_object()) {
      ancestors_.push_back(&node);
      for (const auto& [key, value] : node.items()) {
        const std::string child = path.empty() ? key : path + "." + key;
        if (value.is_string() && EndsWith(key, "Ref") && value.get<std::string>().rfind("sha1-", 0) == 0) {
          Add(path, key, value.get<std::string>());
        } else {
          Walk(value, child, depth + 1);
        }
      }
      ancestors_.pop_back();
    } else if (node.is_array()) {
      for (std::size_t i = 0; i < node.size(); ++i) Walk(node[i], path + "[" + std::to_string(i) + "]", depth + 1);
    }
  }

  std::vector<EmbeddedItem> Take() { return std::move(items_); }

 private:
  void Add(const std::string& parent_path, const std::string& key, const std::string& reference) {
    EmbeddedItem item;
    item.kind = Classify(parent_path, key);
    if (item.kind == ItemKind::kRawImage && modulation_frame_) item.kind = ItemKind::kWhiteImage;
    item.json_path = parent_path.empty() ? key : parent_path + "." + key;
    item.reference = Lower(reference);  // some tools write upper-case hex; section headers are lower-case
    for (std::size_t i = 0; i < container_.sections.size(); ++i) {
      if (container_.sections[i].sha1 == item.reference) {
        item.section = static_cast<int>(i);
        break;
      }
    }
    item.width = IntFromAncestors(ancestors_, "width");
    item.height = IntFromAncestors(ancestors_, "height");
    item.representation = StringFromAncestors(ancestors_, "representation");
    const nlohmann::json& owner = *ancestors_.back();
    if (item.kind == ItemKind::kCalibrationFile) {
      item.name = StringFromAncestors({&owner}, "name");
    } else if (item.kind == ItemKind::kFocusStackImage) {
      for (const char* field : {"lambda", "focus"}) {
        const auto it = owner.find(field);
        if (it != owner.end() && it->is_number()) item.name = "lambda " + FormatNumber(it->get<double>());
      }
    }
    if (item.kind == ItemKind::kRawImage || item.kind == ItemKind::kWhiteImage ||
        item.kind == ItemKind::kFrameMetadata || item.kind == ItemKind::kPrivateMetadata) {
      item.width = item.height = 0;  // the frame's size lives in its metadata, not beside the reference
    }
    items_.push_back(std::move(item));
  }

  static constexpr int kMaxDepth = 100;
  const LfpContainer& container_;
  bool modulation_frame_;
  std::string source_;
  std::vector<const nlohmann::json*> ancestors_;
  std::vector<EmbeddedItem> items_;
};

bool ModulationFlag(const nlohmann::json& frame_entry, const std::string& source) {
  const nlohmann::json* vendor = FindPath(frame_entry, "parameters.vendorContent");
  if (vendor == nullptr || !vendor->is_object() || !vendor->contains("com.lytro.tags")) return false;
  return BoolAt((*vendor)["com.lytro.tags"], "modulationFrame", source).value_or(false);
}

// Frame metadata of a container: behind frame.metadataRef, or inline as frame.metadata (Desktop exports).
void ResolveFrameMetadata(LytroCapture& capture, const nlohmann::json& frame, const std::string& frame_path,
                          bool modulation) {
  const std::string source = capture.path.string();
  nlohmann::json metadata;
  nlohmann::json private_metadata = nlohmann::json::object();
  std::string where;
  if (const nlohmann::json* inline_md = FindPath(frame, "metadata"); inline_md != nullptr) {
    metadata = *inline_md;
    where = source + " (" + frame_path + ".metadata)";
  } else if (const auto ref = StringAt(frame, "metadataRef", source); ref) {
    const LfpSection* section = capture.container.Find(Lower(*ref));
    if (section == nullptr) {
      capture.metadata_problem = frame_path + ".metadataRef " + *ref + " is not in this file";
      return;
    }
    metadata = section->Json(source);
    where = source + " (" + frame_path + ".metadataRef)";
  } else {
    capture.metadata_problem = frame_path + " has neither metadata nor metadataRef";
    return;
  }
  if (const nlohmann::json* inline_private = FindPath(frame, "privateMetadata"); inline_private != nullptr) {
    private_metadata = *inline_private;
  } else if (const auto ref = StringAt(frame, "privateMetadataRef", source); ref) {
    if (const LfpSection* section = capture.container.Find(Lower(*ref)); section != nullptr) {
      private_metadata = section->Json(source);
    }
  }
  capture.metadata = ParseFrameMetadata(metadata, private_metadata, where);
  capture.metadata->modulation_frame = modulation;
}

LytroCapture FromContainer(LfpContainer container, const std::string& source) {
  LytroCapture capture;
  capture.path = source;
  capture.format = "LFP container";
  capture.container = std::move(container);
  capture.toc = capture.container.Toc(source).Json(source);
  const nlohmann::json& toc = capture.toc;

  bool modulation = false;
  if (const nlohmann::json* frame = FindPath(toc, "frames[0]"); frame != nullptr) {
    capture.schema = "Illum picture (frames[])";
    modulation = ModulationFlag(*frame, source);
    if (const nlohmann::json* f = FindPath(*frame, "frame"); f != nullptr) {
      ResolveFrameMetadata(capture, *f, "frames[0].frame", modulation);
    } else {
      capture.metadata_problem = "frames[0] has no frame";
    }
  } else if (const nlohmann::json* entry = FindPath(toc, "picture.frameArray[0]"); entry != nullptr) {
    capture.schema = "F01 picture (picture.frameArray)";
    modulation = ModulationFlag(*entry, source);
    if (const nlohmann::json* f = FindPath(*entry, "frame"); f != nullptr) {
      ResolveFrameMetadata(capture, *f, "picture.frameArray[0].frame", modulation);
    } else {
      capture.metadata_problem = "picture.frameArray[0] has no frame";
    }
  } else if (FindPath(toc, "files") != nullptr) {
    capture.schema = "calibration archive (files[])";
    capture.metadata_problem = "a calibration archive holds files, not a frame";
  } else {
    capture.schema = "unknown table of contents";
    capture.metadata_problem = "the table of contents has neither frames[] nor picture.frameArray[]";
  }
  ItemCollector collector(capture.container, modulation, source);
  collector.Walk(toc, "");
  capture.items = collector.Take();
  return capture;
}

// Extractors such as lfpsplitter write a frame as IMG_0001__frame.raw + IMG_0001__frame.json and its private
// metadata (the camera serial, needed to pick a white image) as IMG_0001__private.json.
void AddSplitterPrivateMetadata(const std::filesystem::path& metadata_path, LytroMetadata& metadata) {
  const std::string stem = metadata_path.stem().string();
  constexpr std::string_view kFrame = "__frame";
  if (!metadata.private_metadata.empty() || !EndsWith(stem, kFrame)) return;
  const std::filesystem::path private_path =
      metadata_path.parent_path() /
      (stem.substr(0, stem.size() - kFrame.size()) + "__private" + metadata_path.extension().string());
  std::error_code ec;
  if (!std::filesystem::is_regular_file(private_path, ec)) return;
  const std::vector<std::uint8_t> bytes = ReadFileBytes(private_path);
  const nlohmann::json private_metadata = ParseLytroJson(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), private_path.string());
  const bool modulation = metadata.modulation_frame;
  const std::string schema = metadata.schema;
  metadata = ParseFrameMetadata(metadata.frame_metadata, private_metadata, metadata.source);
  metadata.modulation_frame = modulation;
  metadata.schema = schema;
}

LytroCapture FromMetadataDocument(const std::filesystem::path& metadata_path, const std::filesystem::path& raw_path) {
  LytroCapture capture;
  const std::vector<std::uint8_t> bytes = ReadFileBytes(metadata_path);
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  capture.toc = ParseLytroJson(text, metadata_path.string());
  capture.metadata = ParseMetadataDocument(text, metadata_path.string());
  capture.schema = capture.metadata->schema;
  AddSplitterPrivateMetadata(metadata_path, *capture.metadata);
  if (raw_path.empty()) {
    capture.path = metadata_path;
    capture.format = "metadata document";
    return capture;
  }
  capture.path = raw_path;
  capture.format = "raw + metadata pair";
  capture.raw_path = raw_path;
  capture.raw_pair_bytes = ReadFileBytes(raw_path);
  EmbeddedItem item;
  item.kind = capture.metadata->modulation_frame ? ItemKind::kWhiteImage : ItemKind::kRawImage;
  item.json_path = raw_path.filename().string();
  item.name = raw_path.filename().string();
  item.section = 0;  // "present": the bytes are in raw_pair_bytes
  if (capture.metadata->raw_format) {
    item.width = capture.metadata->raw_format->width;
    item.height = capture.metadata->raw_format->height;
    item.representation = std::string(ToString(capture.metadata->raw_format->packing));
  }
  capture.items.push_back(item);
  return capture;
}

std::string Plural(std::size_t n, const std::string& what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

}  // namespace

std::string_view ToString(ItemKind kind) {
  switch (kind) {
    case ItemKind::kRawImage:
      return "raw image";
    case ItemKind::kWhiteImage:
      return "white image";
    case ItemKind::kFrameMetadata:
      return "frame metadata";
    case ItemKind::kPrivateMetadata:
      return "private metadata";
    case ItemKind::kDepthMap:
      return "depth map";
    case ItemKind::kConfidenceMap:
      return "confidence map";
    case ItemKind::kDepthLut:
      return "depth LUT";
    case ItemKind::kFocusStackImage:
      return "focus-stack frame";
    case ItemKind::kImageBlock:
      return "image block";
    case ItemKind::kThumbnail:
      return "thumbnail";
    case ItemKind::kCalibrationFile:
      return "calibration file";
    case ItemKind::kOther:
      return "other";
  }
  return "?";
}

bool LytroCapture::HasRawImage() const { return FrameImage() != nullptr; }

bool LytroCapture::IsWhiteImage() const { return metadata && metadata->modulation_frame; }

const EmbeddedItem* LytroCapture::FrameImage() const {
  for (const EmbeddedItem& item : items) {
    // The frame's own image (imageRef), which is a white image in a modulation frame; not a white image that a
    // capture carries beside its raw image (modulationDataRef).
    const bool frame_image = item.kind == ItemKind::kRawImage ||
                             (item.kind == ItemKind::kWhiteImage && !EndsWith(item.json_path, "modulationDataRef"));
    if (item.present() && frame_image) return &item;
  }
  return nullptr;
}

std::span<const std::uint8_t> LytroCapture::RawBytes() const {
  if (!raw_path.empty()) return raw_pair_bytes;
  if (const EmbeddedItem* item = FrameImage(); item != nullptr) {
    return container.sections[static_cast<std::size_t>(item->section)].payload;
  }
  std::string why = "no raw image: this file holds " + HoldsSummary();
  for (const EmbeddedItem& item : items) {
    if (item.kind == ItemKind::kRawImage && !item.present()) {
      why += " (" + item.json_path + " " + item.reference + " is not in the file: a Lytro Desktop export)";
      break;
    }
  }
  throw Error(path.string() + ": " + why);
}

RawImage LytroCapture::ReadRawImage() const {
  const std::span<const std::uint8_t> bytes = RawBytes();
  if (!metadata) throw Error(path.string() + ": raw image found but no frame metadata: " + metadata_problem);
  const RawFormat& raw = metadata->RequireRawFormat();
  return UnpackRawImage(raw.packing, bytes, raw.width, raw.height, path.string() + " raw image");
}

std::vector<const EmbeddedItem*> LytroCapture::ItemsOf(ItemKind kind) const {
  std::vector<const EmbeddedItem*> out;
  for (const EmbeddedItem& item : items) {
    if (item.kind == kind) out.push_back(&item);
  }
  return out;
}

std::vector<std::size_t> LytroCapture::UnreferencedSections() const {
  std::set<std::string> referenced;
  for (const EmbeddedItem& item : items) referenced.insert(item.reference);
  std::vector<std::size_t> out;
  const LfpSection* toc_section = container.FindToc();
  for (std::size_t i = 0; i < container.sections.size(); ++i) {
    const LfpSection& s = container.sections[i];
    if (&s != toc_section && referenced.count(s.sha1) == 0) out.push_back(i);
  }
  return out;
}

std::string LytroCapture::HoldsSummary() const {
  std::map<ItemKind, std::size_t> counts;
  std::map<ItemKind, std::string> sizes;
  for (const EmbeddedItem& item : items) {
    if (!item.present()) continue;
    ++counts[item.kind];
    if (item.width > 0 && item.height > 0)
      sizes[item.kind] = std::to_string(item.width) + "x" + std::to_string(item.height);
  }
  std::vector<std::string> parts;
  for (const auto& [kind, n] : counts) {
    std::string part = Plural(n, std::string(ToString(kind)));
    if (!sizes[kind].empty()) part += " " + sizes[kind];
    parts.push_back(part);
  }
  if (parts.empty()) return "no embedded items";
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? ", " : "") + parts[i];
  return out;
}

std::filesystem::path FindMetadataPartner(const std::filesystem::path& raw_path) {
  for (const char* ext : {".TXT", ".txt", ".json", ".JSON"}) {
    std::filesystem::path candidate = raw_path;
    candidate.replace_extension(ext);
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
  }
  return {};
}

LytroCapture OpenLytroContainerBytes(std::span<const std::uint8_t> bytes, const std::string& source_name) {
  return FromContainer(ParseLfpContainer(bytes, source_name), source_name);
}

LytroCapture OpenLytroCapture(const std::filesystem::path& path) {
  const std::string ext = Lower(path.extension().string());
  if (ext == ".raw") {
    const std::filesystem::path partner = FindMetadataPartner(path);
    if (partner.empty()) {
      throw Error(path.string() + ": raw file without its metadata (no .TXT or .json of the same name beside it)");
    }
    LytroCapture capture = FromMetadataDocument(partner, path);
    return capture;
  }
  std::vector<std::uint8_t> bytes = ReadFileBytes(path);
  if (HasLfpMagic(bytes)) return OpenLytroContainerBytes(bytes, path.string());
  if (ext == ".txt" || ext == ".json") {
    std::filesystem::path raw = path;
    for (const char* raw_ext : {".RAW", ".raw"}) {
      raw.replace_extension(raw_ext);
      std::error_code ec;
      if (std::filesystem::is_regular_file(raw, ec)) return FromMetadataDocument(path, raw);
    }
    return FromMetadataDocument(path, {});
  }
  // Not a known extension: report the container problem (wrong magic, truncation) in the reader's words.
  return OpenLytroContainerBytes(bytes, path.string());
}

}  // namespace lfsp::decode
