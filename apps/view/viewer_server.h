#pragma once

// The viewer's HTTP server: the embedded page, the loaded data as binary arrays, and the export. It serves nothing
// from the file system, so no request path can reach a file it was not started with.

#include <filesystem>
#include <functional>
#include <string>

#include "view/viewer_data.h"

namespace lfsp::view {

struct ServerOptions {
  std::string host = "127.0.0.1";  // loopback only unless asked
  int port = 8765;                 // 0 = any free port
  std::filesystem::path export_folder;
};

// Serves until the process ends; calls `listening(port)` once the port is bound. Throws lfsp::Error naming the
// address when it cannot listen (port in use, not permitted, unknown host).
void Serve(const ViewerData& data, const ServerOptions& options, const std::function<void(int port)>& listening);

}  // namespace lfsp::view
