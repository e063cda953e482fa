#include "view/viewer_server.h"

#include <httplib.h>
#include <spdlog/spdlog.h>

#include <csignal>
#include <mutex>

#include "lfsp/core/error.h"
#include "lfsp/core/untrusted_json.h"
#include "view/viewer_export.h"
#include "view/web_assets.h"

namespace lfsp::view {
namespace {

constexpr std::size_t kLargestRequestBytes = 1 << 20;  // an export request is a few KB
constexpr std::size_t kChunkBytes = 1 << 20;

std::string ContentTypeOf(std::string_view name) {
  if (name.ends_with(".html")) return "text/html; charset=utf-8";
  if (name.ends_with(".js")) return "text/javascript; charset=utf-8";
  if (name.ends_with(".css")) return "text/css; charset=utf-8";
  return "application/octet-stream";
}

// Streams `bytes` (which outlive the server) without copying them into the response.
void ServeBytes(httplib::Response& response, const void* bytes, std::size_t size) {
  const char* begin = static_cast<const char*>(bytes);
  response.set_content_provider(size, "application/octet-stream",
                                [begin, size](std::size_t offset, std::size_t, httplib::DataSink& sink) {
                                  const std::size_t length = std::min(kChunkBytes, size - offset);
                                  return sink.write(begin + offset, length);  // false: the browser went away
                                });
}

void AddPageRoutes(httplib::Server& server) {
  for (const WebAsset& asset : WebAssets()) {
    const std::string path = asset.name == "index.html" ? "/" : "/" + std::string(asset.name);
    server.Get(path, [asset](const httplib::Request&, httplib::Response& response) {
      response.set_content(asset.bytes.data(), asset.bytes.size(), ContentTypeOf(asset.name).c_str());
    });
  }
}

void AddDataRoutes(httplib::Server& server, const ViewerData& data) {
  server.Get("/api/meta", [&data](const httplib::Request&, httplib::Response& response) {
    response.set_content(data.meta.dump(), "application/json");
  });
  server.Get("/api/views", [&data](const httplib::Request&, httplib::Response& response) {
    ServeBytes(response, data.views_rgb8.data(), data.views_rgb8.size());
  });
  server.Get("/api/labels", [&data](const httplib::Request&, httplib::Response& response) {
    ServeBytes(response, data.labels_packed.data(), data.labels_packed.size());
  });
  // Small (one view of floats): made once per request.
  server.Get("/api/disparity", [&data](const httplib::Request&, httplib::Response& response) {
    response.set_content(FloatBytes(data.bundle.disparity), "application/octet-stream");
  });
  server.Get("/api/confidence", [&data](const httplib::Request&, httplib::Response& response) {
    response.set_content(FloatBytes(data.confidence), "application/octet-stream");
  });
}

void AddExportRoute(httplib::Server& server, const ViewerData& data, const std::filesystem::path& folder) {
  static std::mutex one_export_at_a_time;  // they write the same files
  server.Post("/api/export", [&data, folder](const httplib::Request& request, httplib::Response& response) {
    const std::lock_guard lock(one_export_at_a_time);
    try {
      const nlohmann::json edit = ParseUntrustedJson(request.body, "export request");
      const nlohmann::json result = ExportEdit(data, edit, folder);
      spdlog::info("exported: {}", result.at("command").get<std::string>());
      response.set_content(result.dump(), "application/json");
    } catch (const nlohmann::json::exception& error) {
      response.status = 400;
      response.set_content(nlohmann::json{{"error", std::string("export: bad JSON: ") + error.what()}}.dump(),
                           "application/json");
    } catch (const Error& error) {
      response.status = 400;
      response.set_content(nlohmann::json{{"error", error.what()}}.dump(), "application/json");
    }
  });
}

}  // namespace

void Serve(const ViewerData& data, const ServerOptions& options, const std::function<void(int port)>& listening) {
  // A browser closing mid-download must end that one transfer, not the server (this httplib build sends without
  // MSG_NOSIGNAL).
  std::signal(SIGPIPE, SIG_IGN);
  httplib::Server server;
  // httplib's default also sets SO_REUSEPORT, which lets a second viewer share a port in use (and split its
  // requests); SO_REUSEADDR alone allows a quick restart and refuses a port someone listens on.
  server.set_socket_options([](socket_t socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  server.set_payload_max_length(kLargestRequestBytes);
  server.set_read_timeout(10, 0);
  AddPageRoutes(server);
  AddDataRoutes(server, data);
  AddExportRoute(server, data, options.export_folder);

  int port = options.port;
  const bool bound =
      port == 0 ? (port = server.bind_to_any_port(options.host)) > 0 : server.bind_to_port(options.host, port);
  if (!bound) {
    throw Error(options.host + ":" + std::to_string(options.port) +
                ": cannot listen (the port is in use, or the address is not this machine's); choose another with "
                "--port");
  }
  listening(port);
  if (!server.listen_after_bind()) throw Error(options.host + ":" + std::to_string(port) + ": the server stopped");
}

}  // namespace lfsp::view
