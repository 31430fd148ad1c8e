// `rockbake studio` (docs/studio.md): a local HTTP server (cpp-httplib) around a
// StudioSession, serving the page in studio/ and the JSON API of
// docs/studio.md. One thread runs cycles while the page says play; requests
// take the same lock, so each sees the simulation between two cycles.
#pragma once

#include <filesystem>
#include <string>

namespace rockbake {

struct StudioOptions {
  std::filesystem::path preset;
  std::string host = "127.0.0.1";         // only this machine unless told otherwise
  int port = 8631;                        // 0: any free port
  int resolution = 64;                    // preview resolution (grid.resolution while in the studio)
  std::filesystem::path out_dir = "out";  // where bake final writes OUT/<name>/
  std::filesystem::path web_root;         // the page: studio/ in rockbake's data folder (core/data_dir.h)
};

// Serves until SIGINT or SIGTERM, then stops cleanly (a final bake under way
// is cancelled) and returns 0. Prints `studio: http://HOST:PORT/` on stdout
// once it listens. Throws InputError for a bad preset, std::runtime_error when
// the address cannot be bound or the page's files are missing.
int runStudio(const StudioOptions& options);

}  // namespace rockbake
