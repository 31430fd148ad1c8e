#include "http/static_files.h"

#include <algorithm>

#include "core/error.h"
#include "core/input_file.h"
#include "http/json_body.h"

namespace rockbake::http {

namespace fs = std::filesystem;

namespace {

const char* contentType(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".mp4") return "video/mp4";
  if (ext == ".glb") return "model/gltf-binary";
  return "application/octet-stream";
}

}  // namespace

std::optional<fs::path> fileUnder(const fs::path& root, const std::string& relative) {
  if (relative.empty() || relative.front() == '/' || relative.find('\0') != std::string::npos ||
      relative.find('\\') != std::string::npos)
    return std::nullopt;
  for (const auto& part : fs::path(relative))
    if (part == ".." || part == ".") return std::nullopt;
  std::error_code ec;
  const fs::path base = fs::canonical(root, ec);
  if (ec) return std::nullopt;
  const fs::path file = fs::canonical(base / relative, ec);
  if (ec || !fs::is_regular_file(file, ec)) return std::nullopt;
  const auto [end, ignored] = std::mismatch(base.begin(), base.end(), file.begin(), file.end());
  if (end != base.end() || file == base) return std::nullopt;
  return file;
}

std::optional<Response> fileResponse(const fs::path& root, const std::string& relative) {
  const std::optional<fs::path> file = fileUnder(root, relative);
  if (!file) return std::nullopt;
  try {
    const InputFile in(*file, "");  // checked again on the open descriptor: a FIFO swapped in is not waited on
    if (in.size() > kMaxStaticFileBytes) return std::nullopt;
    Response response;
    response.body = in.read(0, in.size());
    response.content_type = contentType(*file);
    response.headers.emplace_back("Cache-Control", "no-cache");
    return response;
  } catch (const InputError&) {
    return std::nullopt;
  }
}

Route staticRoute(const std::string& pattern, const fs::path& root) {
  return {"GET", pattern, [root](const Request& request) {
            std::optional<Response> file = fileResponse(root, request.matches.at(1));
            if (!file) throw HttpError(404, "not found: " + request.path);
            return std::move(*file);
          }};
}

}  // namespace rockbake::http
