#include "studio/studio_server.h"

#include <pthread.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <httplib.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "pipeline/bake_asset.h"
#include "pipeline/read_inputs.h"
#include "preset/schema.h"
#include "preset/yaml_text.h"
#include "studio/studio_session.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr std::size_t kMaxBody = 1 << 20;  // 1 MB: the largest request the API accepts
// Bodies up to this size are read to the end and then refused with 413 and a
// message: a server that closes the connection mid-upload leaves the client
// with a reset instead of the answer. Larger ones are cut off unanswered.
constexpr std::size_t kMaxReadBody = 16 << 20;

void reply(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

void fail(httplib::Response& res, int status, const std::string& message) {
  reply(res, status, {{"error", message}});
}

json parseBody(const httplib::Request& req) {
  if (req.body.size() > kMaxBody) throw StudioError(413, "the request body is over 1 MB");
  try {
    return json::parse(req.body);
  } catch (const json::exception& e) {
    throw StudioError(400, std::string("the request body is not valid JSON: ") + e.what());
  }
}

// A palette by the preset's names for it (bake.palette), "durability" being the debug palette's other name.
PreviewPalette previewPalette(const std::string& name) {
  const std::optional<Palette> palette = name == "durability" ? Palette::Debug : schema::valueNamed<Palette>(name);
  if (!palette) throw StudioError(400, "palette: expected " + joinNamesWith(schema::namesOf<Palette>(), "or"));
  switch (*palette) {
    case Palette::Natural:
      return PreviewPalette::Natural;
    case Palette::Debug:
      return PreviewPalette::Durability;
    case Palette::Curvature:
      return PreviewPalette::Curvature;
  }
  return PreviewPalette::Natural;
}

const char* contentType(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  return "application/octet-stream";
}

// A file strictly inside `root`, by a relative path from a URL; nullopt for
// anything else (parent steps, absolute paths, links leading out, folders).
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
  if (end != base.end()) return std::nullopt;
  return file;
}

bool serveFile(httplib::Response& res, const fs::path& root, const std::string& relative) {
  const auto file = fileUnder(root, relative);
  if (!file) return false;
  std::ifstream in(*file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  res.status = 200;
  res.set_content(bytes.str(), contentType(*file));
  res.set_header("Cache-Control", "no-cache");
  return true;
}

struct BakeStatus {
  std::string state = "idle";  // idle, running, done, failed
  double progress = 0.0;
  std::string message;
  std::string asset_dir;
};

}  // namespace

int runStudio(const StudioOptions& options) {
  const fs::path web_root = options.web_root;
  const fs::path three_root = web_root / "node_modules" / "three";
  for (const fs::path& needed : {web_root / "index.html", three_root / "build" / "three.module.js"})
    if (!fs::is_regular_file(needed))
      throw std::runtime_error(
          "the studio page is missing " + needed.string() +
          "; in a source build run scripts/setup.sh (it installs studio/node_modules from the lock file), "
          "else install rockbake again (cmake --install lays the page out in share/rockbake/studio)");

  // Ctrl-C (and SIGTERM) go to a thread of their own, which stops the server
  // between requests. Blocked first, so that every thread started from here on
  // (TBB's workers, the server's) inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGUSR1);  // our own wake-up when listening fails
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  struct Unblock {
    sigset_t* set;
    ~Unblock() { pthread_sigmask(SIG_UNBLOCK, set, nullptr); }
  } unblock{&signals};

  StudioSession session(options.preset, options.resolution);
  std::mutex mutex;  // guards session, bake status and the mesh cache
  std::condition_variable wake;
  std::atomic<bool> playing{false}, stopping{false}, bake_cancel{false};
  std::atomic<double> rate{0.0};  // cycles per second while playing; 0: as fast as they run
  BakeStatus bake;
  std::thread bake_thread;
  std::map<int, std::pair<std::uint64_t, std::shared_ptr<const std::string>>> mesh_cache;  // by palette

  // The simulation thread: a cycle at a time while playing, the lock released between cycles.
  std::thread runner([&] {
    std::unique_lock lock(mutex);
    while (!stopping) {
      if (!playing) {
        wake.wait_for(lock, std::chrono::milliseconds(200));
        continue;
      }
      if (session.atEnd()) {
        playing = false;
        continue;
      }
      const auto started = std::chrono::steady_clock::now();
      try {
        session.step();
      } catch (const std::exception& e) {
        spdlog::error("studio: the simulation stopped: {}", e.what());
        playing = false;
      }
      // Let a waiting request in between cycles; at a set rate, wait out the rest of the cycle's time.
      const double r = rate.load();
      const auto due = r > 0 ? started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(1.0 / r))
                             : std::chrono::steady_clock::now() + std::chrono::milliseconds(1);
      lock.unlock();
      std::this_thread::sleep_until(due);
      lock.lock();
    }
  });

  const auto stateJson = [&] {
    json s = session.state();
    s["playing"] = playing.load();
    s["rate"] = rate.load();
    s["bake"] = {
        {"state", bake.state}, {"progress", bake.progress}, {"message", bake.message}, {"asset_dir", bake.asset_dir}};
    return s;
  };
  // Runs `handler` under the lock, turning refusals into 4xx answers.
  const auto guarded = [&](auto&& handler) {
    return [&, handler](const httplib::Request& req, httplib::Response& res) {
      try {
        std::unique_lock lock(mutex);
        handler(req, res);
      } catch (const StudioError& e) {
        fail(res, e.status(), e.what());
      } catch (const InputError& e) {
        fail(res, 400, e.what());
      }
    };
  };

  httplib::Server server;
  server.set_payload_max_length(kMaxReadBody);
  server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    std::string message = "HTTP " + std::to_string(res.status);
    if (res.status == 404) message = "not found: " + req.path;
    if (res.status == 413) message = "the request body is over 1 MB";
    if (res.status == 400) message = "bad request";
    fail(res, res.status, message);
  });
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
    std::string message = "internal error";
    try {
      std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      message = e.what();
    } catch (...) {
    }
    spdlog::error("studio: {}", message);
    fail(res, 500, message);
  });

  server.Get("/api/state",
             guarded([&](const httplib::Request&, httplib::Response& res) { reply(res, 200, stateJson()); }));

  server.Post(
      "/api/control", guarded([&](const httplib::Request& req, httplib::Response& res) {
        json body = parseBody(req);
        if (body.is_string()) body = {{"action", body}};
        if (!body.is_object() || body.empty() || (body.size() > 1 && !(body.size() == 2 && body.contains("rate"))))
          throw StudioError(
              400, R"(expected one of {"action": "play"|"pause"|"step"|"reset"}, {"run_until": t}, {"seek": t})");
        const auto number = [&](const char* key) {
          if (!body[key].is_number()) throw StudioError(400, std::string(key) + ": expected a time (a number >= 0)");
          return body[key].get<double>();
        };
        if (body.contains("action")) {
          const std::string action = body["action"].is_string() ? body["action"].get<std::string>() : "";
          if (action == "play") {
            const json requested = body.value("rate", json(0.0));
            if (!requested.is_number() || requested.get<double>() < 0 || requested.get<double>() > 1000)
              throw StudioError(400, "rate: expected cycles per second, 0 (as fast as they run) to 1000");
            rate = requested.get<double>();
            playing = true;
            wake.notify_all();
          } else if (action == "pause") {
            playing = false;
          } else if (action == "step") {
            playing = false;
            session.step();
          } else if (action == "reset") {
            playing = false;
            session.reset();
          } else {
            throw StudioError(400, "action: expected play, pause, step or reset");
          }
        } else if (body.contains("run_until")) {
          playing = false;
          session.runUntil(number("run_until"));
        } else if (body.contains("seek")) {
          playing = false;
          session.seek(number("seek"));
        } else {
          throw StudioError(400, "expected action, run_until or seek");
        }
        reply(res, 200, stateJson());
      }));

  server.Post("/api/edit", guarded([&](const httplib::Request& req, httplib::Response& res) {
                session.edit(parseBody(req));
                reply(res, 200, stateJson());
              }));

  server.Post(
      "/api/save", guarded([&](const httplib::Request& req, httplib::Response& res) {
        const json body = parseBody(req);
        if (!body.is_object() || !body.contains("name") || !body["name"].is_string())
          throw StudioError(400, R"(expected {"name": "asset-name", "overwrite": false})");
        const bool overwrite = body.value("overwrite", false);
        const SaveResult saved = session.save(body["name"].get<std::string>(), overwrite);
        spdlog::info("studio: saved {} at time {}", saved.path.string(), saved.time);
        reply(res, 200, {{"path", saved.path.string()}, {"time", saved.time}, {"preset_hash", saved.preset_hash}});
      }));

  server.Get("/api/rock.vdb", guarded([&](const httplib::Request&, httplib::Response& res) {
               res.set_content(session.rockVdb(), "application/octet-stream");
             }));

  server.Get("/api/mesh", guarded([&](const httplib::Request& req, httplib::Response& res) {
               const PreviewPalette palette =
                   previewPalette(req.has_param("palette") ? req.get_param_value("palette") : "natural");
               auto& cached = mesh_cache[int(palette)];
               if (!cached.second || cached.first != session.rockVersion())
                 cached = {session.rockVersion(), std::make_shared<const std::string>(session.previewMesh(palette))};
               res.set_header("X-Mesh-Version", std::to_string(cached.first));
               res.set_content(*cached.second, "application/octet-stream");
             }));

  server.Post("/api/bake", guarded([&](const httplib::Request& req, httplib::Response& res) {
                if (!req.body.empty()) parseBody(req);
                if (bake.state == "running") throw StudioError(409, "a final bake is already running");
                Preset preset = session.finalPreset();
                ResolvedShape shape = readInputs(preset);
                if (bake_thread.joinable()) bake_thread.join();
                bake = {"running", 0.0, "starting", (options.out_dir / preset.name).string()};
                bake_cancel = false;
                bake_thread = std::thread([&, preset = std::move(preset), shape = std::move(shape)] {
                  BakeOptions bake_options;
                  bake_options.out_dir = options.out_dir;
                  bake_options.cancel = &bake_cancel;
                  bake_options.progress = [&](double fraction, const std::string& stage) {
                    std::lock_guard lock(mutex);
                    bake.progress = fraction;
                    bake.message = stage;
                  };
                  std::string state = "done", message;
                  try {
                    const BakeSummary summary = bakeAsset(preset, shape, bake_options);
                    message = fmt::format("{} cycles in {:.1f} s → {}", summary.cycles, summary.seconds,
                                          summary.asset_dir.string());
                  } catch (const std::exception& e) {
                    state = "failed";
                    message = e.what();
                  }
                  std::lock_guard lock(mutex);
                  bake.state = state;
                  bake.message = message;
                  if (state == "done") bake.progress = 1.0;
                });
                reply(res, 202, {{"asset_dir", bake.asset_dir}});
              }));

  // The page and its pinned JavaScript; nothing else.
  server.Get("/", [&](const httplib::Request&, httplib::Response& res) { serveFile(res, web_root, "index.html"); });
  server.Get(R"(/(studio\.js|studio\.css))",
             [&](const httplib::Request& req, httplib::Response& res) { serveFile(res, web_root, req.matches[1]); });
  server.Get(R"(/vendor/three/((build|examples/jsm)/.+))", [&](const httplib::Request& req, httplib::Response& res) {
    if (!serveFile(res, three_root, req.matches[1])) fail(res, 404, "not found: " + req.path);
  });

  std::thread signal_thread([&] {
    int signal = 0;
    sigwait(&signals, &signal);
    stopping = true;
    bake_cancel = true;
    wake.notify_all();
    server.stop();
  });

  const int port = options.port == 0 ? server.bind_to_any_port(options.host)
                                     : (server.bind_to_port(options.host, options.port) ? options.port : -1);
  bool listened = false;
  if (port > 0) {
    std::cout << "studio: http://" << options.host << ":" << port << "/" << std::endl;
    spdlog::info("studio: {} at resolution {}; Ctrl-C stops", session.preset().name, options.resolution);
    listened = server.listen_after_bind();
  }
  if (!stopping) pthread_kill(signal_thread.native_handle(), SIGUSR1);
  signal_thread.join();
  stopping = true;
  wake.notify_all();
  runner.join();
  if (bake_thread.joinable()) bake_thread.join();
  if (port <= 0)
    throw std::runtime_error(
        fmt::format("cannot listen on {}:{} (in use, or not an address of this machine); "
                    "try another --port or --port 0",
                    options.host, options.port));
  if (!listened && !server.is_running()) spdlog::info("studio: stopped");
  return 0;
}

}  // namespace rockbake
