// The studio's JSON API and page (docs/studio.md), as a route table for the
// HTTP layer (http/local_server.h): one function per endpoint. Each runs under
// the studio's lock, so it sees the simulation between two cycles; refusals are
// 4xx with a message (StudioError, InputError), and running out of memory is a
// 503 that leaves the session as it was (or at its latest checkpoint).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "http/route.h"
#include "studio/final_bake.h"
#include "studio/simulation_loop.h"
#include "studio/studio_session.h"

namespace rockbake {

// What the routes, the play loop and the final bake share. Members are made
// in order (the session, then the threads that use it) and stopped in reverse.
struct Studio {
  Studio(StudioSession& studio_session, std::filesystem::path out_dir)
      : session(studio_session), loop(session, mutex), bake(std::move(out_dir)) {}

  StudioSession& session;
  std::mutex mutex;  // guards the session, the loop's state and the mesh cache
  SimulationLoop loop;
  FinalBake bake;
  // The last preview mesh per palette, with the rock version it shows.
  std::map<Palette, std::pair<std::uint64_t, std::shared_ptr<const std::string>>> meshes;
};

// GET /api/state, /api/rock.vdb, /api/mesh, /api/final/… (the last finished final bake's
// rock.glb and textures/*.png); POST /api/control, /api/edit, /api/save, /api/bake; the page from `web_root` (/,
// /studio.css, /js/*.js) and the pinned three.js from web_root/node_modules/three (/vendor/three/...).
std::vector<http::Route> studioRoutes(Studio& studio, const std::filesystem::path& web_root);

}  // namespace rockbake
