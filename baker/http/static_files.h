// Files a local server serves from a folder of its own (docs/studio.md,
// "Static files"): only regular files strictly inside the folder, named by a
// relative path from the URL. Parent steps, absolute paths, backslashes, NUL,
// links that lead out, folders, FIFOs and devices are not served (404), in any
// encoding (the path is matched after percent-decoding, and the file found is
// checked again after links are resolved).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "http/route.h"

namespace rockbake::http {

// A served file is at most this large (the studio's largest, three.js, is 1.2 MB).
inline constexpr std::uint64_t kMaxStaticFileBytes = std::uint64_t(64) << 20;

// The file `relative` names under `root`, resolved, or nothing (see above).
std::optional<std::filesystem::path> fileUnder(const std::filesystem::path& root, const std::string& relative);

// The file as a 200 answer (Content-Type by extension, Cache-Control: no-cache),
// or nothing when fileUnder finds none or it cannot be read.
std::optional<Response> fileResponse(const std::filesystem::path& root, const std::string& relative);

// fileResponse with the page's Content-Security-Policy: scripts, styles and
// media from this server only, its own inline scripts by hash, no framing.
std::optional<Response> pageResponse(const std::filesystem::path& root, const std::string& relative);

// A GET route: `pattern`'s first group is the path under `root`; 404 when no such file.
Route staticRoute(const std::string& pattern, const std::filesystem::path& root);

// staticRoute for files nobody vetted (a baked library's OUT, where anyone may
// have put a file): PNG, MP4, GLB and JSON are shown with their types, anything
// else (HTML, SVG, scripts) is an attachment of type application/octet-stream,
// and every one is sandboxed (Content-Security-Policy: sandbox), so a planted
// page never runs as this server's own.
Route libraryFilesRoute(const std::string& pattern, const std::filesystem::path& root);

}  // namespace rockbake::http
