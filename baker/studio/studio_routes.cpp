#include "studio/studio_routes.h"

#include <new>
#include <optional>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "http/json_body.h"
#include "http/static_files.h"
#include "pipeline/read_inputs.h"
#include "preset/schema.h"
#include "preset/yaml_text.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using http::HttpError;
using http::Request;
using http::Response;
using nlohmann::json;

json stateJson(const Studio& studio) {
  json state = studio.session.state();
  state["playing"] = studio.loop.playing();
  state["rate"] = studio.loop.rate();
  state["problem"] = studio.loop.lastProblem();
  const BakeStatus bake = studio.bake.status();
  state["bake"] = {
      {"state", bake.state}, {"progress", bake.progress}, {"message", bake.message}, {"asset_dir", bake.asset_dir}};
  return state;
}

Response getState(Studio& studio, const Request&, const json&) {
  return http::jsonResponse(stateJson(studio));
}

// {"action": "play" (with "rate"), "pause", "step" or "reset"}, {"run_until": t} or {"seek": t}.
Response postControl(Studio& studio, const Request&, const json& request_body) {
  json body = request_body;
  if (body.is_string()) body = {{"action", body}};
  const std::string shape = R"({"action": "play"|"pause"|"step"|"reset"}, {"run_until": t} or {"seek": t})";
  if (!body.is_object() || body.empty() || (body.size() > 1 && !(body.size() == 2 && body.contains("rate"))))
    throw HttpError(400, "expected one of " + shape);
  const auto time = [&](const char* key) { return http::numberValue(body[key], key, "a time (a number >= 0)"); };
  if (body.contains("action")) {
    const std::string action = body["action"].is_string() ? body["action"].get<std::string>() : "";
    if (action == "play") {
      const std::string rate_is = "cycles per second, 0 (as fast as they run) to 1000";
      const double rate = body.contains("rate") ? http::numberValue(body["rate"], "rate", rate_is) : 0.0;
      if (rate < 0 || rate > 1000) throw HttpError(400, "rate: expected " + rate_is);
      studio.loop.play(rate);
    } else if (action == "pause") {
      studio.loop.pause();
    } else if (action == "step") {
      studio.loop.pause();
      studio.session.step();
    } else if (action == "reset") {
      studio.loop.pause();
      studio.session.reset();
    } else {
      throw HttpError(400, "action: expected play, pause, step or reset");
    }
  } else if (body.contains("run_until")) {
    studio.loop.pause();
    studio.session.runUntil(time("run_until"));
  } else if (body.contains("seek")) {
    studio.loop.pause();
    studio.session.seek(time("seek"));
  } else {
    throw HttpError(400, "expected one of " + shape);
  }
  return http::jsonResponse(stateJson(studio));
}

Response postEdit(Studio& studio, const Request&, const json& body) {
  studio.session.edit(body);
  return http::jsonResponse(stateJson(studio));
}

Response postSave(Studio& studio, const Request&, const json& body) {
  const std::string shape = R"({"name": "asset-name", "overwrite": false})";
  const std::string name = http::stringMember(body, "name", shape);
  const SaveResult saved = studio.session.save(name, http::boolMember(body, "overwrite", false));
  spdlog::info("studio: saved {} at time {}", saved.path.string(), saved.time);
  return http::jsonResponse({{"path", saved.path.string()}, {"time", saved.time}, {"preset_hash", saved.preset_hash}});
}

Response getRockVdb(Studio& studio, const Request&, const json&) {
  return {200, "application/octet-stream", studio.session.rockVdb(), {}};
}

// ?palette= by the preset's names for them (bake.palette), "durability" being the debug palette's other name.
Palette paletteNamed(const std::string& name) {
  const std::optional<Palette> palette = name == "durability" ? Palette::Debug : schema::valueNamed<Palette>(name);
  if (!palette) throw HttpError(400, "palette: expected " + joinNamesWith(schema::namesOf<Palette>(), "or"));
  return *palette;
}

Response getMesh(Studio& studio, const Request& request, const json&) {
  const Palette palette = paletteNamed(request.param("palette").value_or("natural"));
  auto& [version, bytes] = studio.meshes[palette];
  if (!bytes || version != studio.session.rockVersion()) {
    bytes.reset();  // the old mesh's memory first
    bytes = std::make_shared<const std::string>(studio.session.previewMesh(palette));
    version = studio.session.rockVersion();
  }
  return {200, "application/octet-stream", *bytes, {{"X-Mesh-Version", std::to_string(version)}}};
}

Response postBake(Studio& studio, const Request&, const json&) {
  Preset preset = studio.session.finalPreset();
  ResolvedShape shape = readInputs(preset);
  const fs::path asset_dir = studio.bake.start(std::move(preset), std::move(shape));
  return http::jsonResponse({{"asset_dir", asset_dir.string()}}, 202);
}

// GET /api/final/<file>: LOD0's GLB and its maps from the last final bake that finished, for the
// page's final view. Not under the studio's lock: the bake's status has a lock of its own, and the
// files are the finished bake's.
Response getFinalFile(const Studio& studio, const Request& request) {
  const BakeStatus bake = studio.bake.status();
  if (bake.state != "done")
    throw HttpError(404, "no final bake has finished" +
                             (bake.state == "idle" ? std::string() : " (the last one is " + bake.state + ")") +
                             ": press Bake final and wait for it to finish");
  std::optional<Response> file = http::fileResponse(bake.asset_dir, request.matches[1]);
  if (file) return std::move(*file);
  const std::optional<fs::path> found = http::fileUnder(bake.asset_dir, request.matches[1]);
  std::error_code error;
  if (found && fs::file_size(*found, error) > http::kMaxStaticFileBytes && !error)
    throw HttpError(413, request.matches[1] + " is larger than the " + std::to_string(http::kMaxStaticFileBytes >> 20) +
                             " MiB the studio serves: open " + found->string() + " itself");
  throw HttpError(404, request.matches[1] + " is not in the final bake's folder " + bake.asset_dir);
}

// An endpoint with its request's JSON body (null when it takes none).
using Endpoint = Response (*)(Studio&, const Request&, const json& body);
enum class Body { None, Required, Optional };  // Optional: an empty body is {}

// Runs `endpoint` under the studio's lock; the session's refusals become the HTTP layer's.
http::Handler locked(Studio& studio, Endpoint endpoint, Body takes = Body::None) {
  return [&studio, endpoint, takes](const Request& request) {
    try {
      // Parsed before the lock: a large body costs its own worker's time, not every request's wait.
      const json body = takes == Body::None                               ? json()
                        : takes == Body::Optional && request.body.empty() ? json::object()
                                                                          : http::parseJsonBody(request);
      std::lock_guard lock(studio.mutex);
      studio.session.recover();
      return endpoint(studio, request, body);
    } catch (const StudioError& e) {
      throw HttpError(e.status(), e.what());
    } catch (const InputError& e) {
      throw HttpError(400, e.what());
    } catch (const std::bad_alloc&) {
      throw HttpError(503, "out of memory answering " + request.method + " " + request.path +
                               "; the studio carries on: close other programs, or restart it at a lower --resolution");
    }
  };
}

}  // namespace

std::vector<http::Route> studioRoutes(Studio& studio, const fs::path& web_root) {
  return {
      {"GET", "/api/state", locked(studio, getState)},
      {"POST", "/api/control", locked(studio, postControl, Body::Required)},
      {"POST", "/api/edit", locked(studio, postEdit, Body::Required)},
      {"POST", "/api/save", locked(studio, postSave, Body::Required)},
      {"GET", "/api/rock\\.vdb", locked(studio, getRockVdb)},
      {"GET", "/api/mesh", locked(studio, getMesh)},
      {"POST", "/api/bake", locked(studio, postBake, Body::Optional)},
      {"GET", R"(/api/final/(rock\.glb|textures/[A-Za-z0-9_.-]+\.png))",
       [&studio](const Request& request) { return getFinalFile(studio, request); }},
      // The page and its pinned JavaScript; nothing else.
      {"GET", "/",
       [web_root](const Request&) {
         std::optional<Response> page = http::pageResponse(web_root, "index.html");
         if (!page) throw HttpError(404, "the page is missing from " + web_root.string());
         return std::move(*page);
       }},
      http::staticRoute(R"(/(studio\.css|studio\.js|js/[a-z_]+\.js))", web_root),
      http::staticRoute(R"(/vendor/three/((build|examples/jsm)/.+))", web_root / "node_modules" / "three"),
  };
}

}  // namespace rockbake
