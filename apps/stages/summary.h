#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

namespace lfsp::stages {

// Every stage and command that writes results also writes a small JSON summary (inputs, parameters, timings,
// metrics), atomically, e.g. OUT.summary.json beside OUT. An ordered summary keeps the order it was filled in. Every
// summary starts with "version", lfsp's version (lfsp/core/version.h), so a result names the lfsp that made it.
void WriteJsonSummary(const nlohmann::json& summary, const std::filesystem::path& path);
void WriteJsonSummary(const nlohmann::ordered_json& summary, const std::filesystem::path& path);

// The summary path for an output: OUT.h5 -> OUT.summary.json, a folder DIR -> DIR/summary.json.
std::filesystem::path SummaryPathFor(const std::filesystem::path& output);

}  // namespace lfsp::stages
