// `rockbake studio` (docs/studio.md): a StudioSession served on the local HTTP
// layer (http/local_server.h, with its limits and who-may-call rules) by the
// route table of studio/studio_routes.h, with a play loop
// (studio/simulation_loop.h), a final bake (studio/final_bake.h) and Ctrl-C
// (http/serve_until_stopped.h) beside it.
#pragma once

#include <filesystem>
#include <string>

#include "http/local_server.h"

namespace rockbake {

struct StudioOptions {
  std::filesystem::path preset;
  std::string host = "127.0.0.1";         // only this machine unless told otherwise
  int port = 8631;                        // 0: any free port
  int resolution = 64;                    // preview resolution (grid.resolution while in the studio)
  std::filesystem::path out_dir = "out";  // where bake final writes OUT/<name>/
  std::filesystem::path web_root;         // the page: studio/ in rockbake's data folder (platform/data_dir.h)
};

// The HTTP layer's limits as the studio sets them (docs/studio.md, "The server's promises").
http::Limits studioLimits();

// Serves until SIGINT or SIGTERM, then stops cleanly (a final bake under way
// is cancelled) and returns 0. Prints `studio: http://HOST:PORT/` on stdout
// once it listens. Throws InputError for a bad preset (a FIFO or a device
// included), std::runtime_error when the address cannot be bound or the page's
// files are missing.
int runStudio(const StudioOptions& options);

}  // namespace rockbake
