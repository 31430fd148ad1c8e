#include "http/static_files.h"

#include <algorithm>

#include "core/error.h"
#include "core/sha256.h"
#include "http/json_body.h"
#include "platform/input_file.h"

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
  if (ext == ".wasm") return "application/wasm";  // three.js's Basis Universal transcoder (docs/review.md)
  return "application/octet-stream";
}

// A file of OUT shown in place: only types no browser runs (an image, a movie,
// a model, JSON). Anything else (a planted page, SVG or script) is a download.
const char* inertType(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".png") return "image/png";
  if (ext == ".mp4") return "video/mp4";
  if (ext == ".glb") return "model/gltf-binary";
  if (ext == ".json") return "application/json";
  return nullptr;
}

std::string base64(const std::string& bytes) {
  static const char* const digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? std::uint8_t(bytes[i + k]) : 0);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? digits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// 'sha256-…' for each inline <script> of the page (the import map), so the
// policy lets those run and no other inline script.
std::string inlineScriptHashes(const std::string& html) {
  std::string hashes;
  for (std::size_t at = html.find("<script"); at != std::string::npos; at = html.find("<script", at + 1)) {
    const std::size_t open_end = html.find('>', at);
    if (open_end == std::string::npos) break;
    if (html.find(" src=", at) < open_end) continue;
    const std::size_t close = html.find("</script>", open_end);
    if (close == std::string::npos) break;
    const std::string hex = sha256Hex(std::string_view(html).substr(open_end + 1, close - open_end - 1));
    std::string digest;
    for (std::size_t i = 0; i + 1 < hex.size(); i += 2) digest += char(std::stoi(hex.substr(i, 2), nullptr, 16));
    hashes += " 'sha256-" + base64(digest) + "'";
  }
  return hashes;
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

std::optional<Response> pageResponse(const fs::path& root, const std::string& relative) {
  std::optional<Response> page = fileResponse(root, relative);
  if (!page) return std::nullopt;
  // Scripts, styles, data and media from this server only (three.js makes blob:
  // URLs for a GLB's images); no plug-ins, no other page framing it. 'unsafe-eval': the
  // compressed set's decoders (docs/delivery.md) compile WebAssembly, and three.js's Basis
  // Universal transcoder (Emscripten's embind, in a blob: worker that has the page's policy)
  // makes its bindings with new Function; inline scripts stay limited to the page's own.
  page->headers.emplace_back(
      "Content-Security-Policy",
      "default-src 'self'; script-src 'self'" + inlineScriptHashes(page->body) +
          " 'unsafe-eval'; style-src 'self'; img-src 'self' blob: data:; media-src 'self' blob:; "
          "connect-src 'self' blob: data:; worker-src 'self' blob:; object-src 'none'; "
          "base-uri 'none'; form-action 'self'; frame-ancestors 'none'");
  return page;
}

Route libraryFilesRoute(const std::string& pattern, const fs::path& root) {
  return {"GET", pattern, [root](const Request& request) {
            std::optional<Response> file = fileResponse(root, request.matches.at(1));
            if (!file) throw HttpError(404, "not found: " + request.path);
            const std::string name = fs::path(request.matches.at(1)).filename().string();
            if (const char* type = inertType(name)) {
              file->content_type = type;
            } else {
              file->content_type = "application/octet-stream";
              file->headers.emplace_back("Content-Disposition", "attachment");
            }
            // Opened as a page all the same (an old browser, a save and reopen), it runs nothing.
            file->headers.emplace_back("Content-Security-Policy",
                                       "sandbox; default-src 'none'; frame-ancestors 'none'");
            return std::move(*file);
          }};
}

Route staticRoute(const std::string& pattern, const fs::path& root) {
  return {"GET", pattern, [root](const Request& request) {
            std::optional<Response> file = fileResponse(root, request.matches.at(1));
            if (!file) throw HttpError(404, "not found: " + request.path);
            return std::move(*file);
          }};
}

}  // namespace rockbake::http
