#include "studio/studio_server.h"

#include <algorithm>
#include <iostream>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "core/memory.h"
#include "studio/stop_signals.h"
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
  StopSignals signals;  // first: every thread from here on inherits the blocked mask
  // The checkpoints take at most an eighth of what this process may use, and 256 MiB.
  CheckpointBounds checkpoints;
  checkpoints.max_bytes = std::min<std::uint64_t>(checkpoints.max_bytes, memoryLimitBytes() / 8);
  StudioSession session(options.preset, options.resolution, checkpoints);
  Studio studio(session, options.out_dir);
  http::LocalServer server(studioRoutes(studio, options.web_root), studioLimits());
  try {
    server.listen(options.host, options.port);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(e.what()) +
                             " (in use, or not an address of this machine); try another --port or --port 0");
  }
  signals.whenReceived([&] {
    studio.bake.cancel();
    server.stop();
  });
  std::cout << "studio: " << server.url() << std::endl;
  spdlog::info("studio: {} at resolution {}; Ctrl-C stops", session.preset().name, options.resolution);
  server.serve();
  spdlog::info("studio: stopped");
  return 0;
}

}  // namespace rockbake
