#include "studio/studio_server.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "http/serve_until_stopped.h"
#include "platform/memory.h"
#include "studio/studio_routes.h"
#include "studio/studio_session.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

void requirePage(const fs::path& web_root) {
  for (const fs::path& needed :
       {web_root / "index.html", web_root / "node_modules" / "three" / "build" / "three.module.js"})
    if (!fs::is_regular_file(needed))
      throw std::runtime_error(
          "the studio page is missing " + needed.string() +
          "; in a source build run scripts/setup.sh (it installs studio/node_modules from the lock file), "
          "else install rockbake again (cmake --install lays the page out in share/rockbake/studio)");
}

}  // namespace

http::Limits studioLimits() {
  http::Limits limits;  // the layer's defaults (http/local_server.h) suit the page: its bodies are small
  limits.workers = 4;   // requests take the studio's lock one at a time; more only queue behind it
  return limits;
}

int runStudio(const StudioOptions& options) {
  requirePage(options.web_root);
  http::StopSignals signals;  // first: every thread from here on inherits the blocked mask
  // The checkpoints take at most an eighth of what this process may use, and 256 MiB.
  CheckpointBounds checkpoints;
  checkpoints.max_bytes = std::min<std::uint64_t>(checkpoints.max_bytes, memoryLimitBytes() / 8);
  StudioSession session(options.preset, options.resolution, checkpoints);
  Studio studio(session, options.out_dir);
  http::LocalServer server(studioRoutes(studio, options.web_root), studioLimits());
  http::serveUntilStopped(signals, server,
                          {"studio", options.host, options.port,
                           fmt::format("{} at resolution {}", session.preset().name, options.resolution)},
                          [&] { studio.bake.cancel(); });
  return 0;
}

}  // namespace rockbake
