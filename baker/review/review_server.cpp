#include "review/review_server.h"

#include <regex>
#include <stdexcept>

#include "core/error.h"
#include "http/json_body.h"
#include "http/local_server.h"
#include "http/serve_until_stopped.h"
#include "http/static_files.h"
#include "review/library_view.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const char* const kReviewShape =
    R"(expected {"asset": NAME, "status": "approved" | "needs-work" | "rejected", "note": TEXT})";

// What index.json says, for a request: an index that cannot be read is the
// library's to fix (409 with what to do), not the request's.
template <typename F>
auto withIndex(F read) {
  try {
    return read();
  } catch (const InputError& e) {
    throw http::HttpError(409, e.what());
  }
}

// review.json's verdicts; a file that is not a review file is the caller's to fix (409).
json verdictsOrRefuse(const ReviewStore& store) {
  try {
    return store.verdicts();
  } catch (const std::runtime_error& e) {
    throw http::HttpError(409, e.what());
  }
}

http::Response postReview(const ReviewOptions& options, ReviewStore& store, const http::Request& request) {
  const json body = http::parseJsonBody(request);
  const std::string asset = http::stringMember(body, "asset", kReviewShape);
  const std::string status = http::stringMember(body, "status", kReviewShape);
  const std::string note = body.contains("note") ? http::stringMember(body, "note", kReviewShape) : "";
  if (!isVerdictStatus(status))
    throw http::HttpError(400, "status '" + status + "' is not a verdict: use approved, needs-work or rejected");
  if (note.size() > kMaxNoteBytes)
    throw http::HttpError(413, "the note has " + std::to_string(note.size()) + " bytes; at most " +
                                   std::to_string(kMaxNoteBytes) + " are kept: shorten it");
  std::string input_hash;
  bool found = false;
  for (const json& entry : withIndex([&] { return libraryIndexAssets(options.library_dir); }))
    if (entry.is_object() && entry.contains("name") && entry["name"] == asset) {
      found = true;
      if (entry.contains("input_hash") && entry["input_hash"].is_string()) input_hash = entry["input_hash"];
    }
  if (!found)
    throw http::HttpError(404, "no asset '" + asset + "' in " + (options.library_dir / "index.json").string());
  try {
    const Verdict stored = store.save(asset, {status, note, input_hash, ""});
    return http::jsonResponse(
        {{"asset", asset},
         {"review",
          {{"status", stored.status}, {"note", stored.note}, {"updated", stored.updated}, {"stale", false}}}});
  } catch (const std::runtime_error& e) {
    throw http::HttpError(409, e.what());
  }
}

void requirePage(const ReviewOptions& options) {
  for (const fs::path& needed : {options.web_root / "index.html", options.three_root / "build" / "three.module.js"})
    if (!fs::is_regular_file(needed))
      throw std::runtime_error(
          "the review page is missing " + needed.string() +
          "; in a source build run scripts/setup.sh (it installs studio/node_modules from the lock file), "
          "else install rockbake again (cmake --install lays the page out in share/rockbake/review)");
}

}  // namespace

std::vector<http::Route> reviewRoutes(const ReviewOptions& options, ReviewStore& store) {
  const fs::path out = options.library_dir;
  return {
      {"GET", "/api/assets",
       [&store, out](const http::Request&) {
         const json verdicts = verdictsOrRefuse(store);
         return http::jsonResponse({{"assets", withIndex([&] { return assetSummaries(out, verdicts); })}});
       }},
      {"GET", R"(/api/assets/([^/]+))",
       [&store, out](const http::Request& request) {
         const std::string name = request.matches.at(1);
         const json verdicts = verdictsOrRefuse(store);
         const auto detail = withIndex([&] { return assetDetail(out, name, verdicts); });
         if (!detail) throw http::HttpError(404, "no asset '" + name + "' in " + (out / "index.json").string());
         return http::jsonResponse(*detail);
       }},
      {"POST", "/api/review",
       [&store, options](const http::Request& request) { return postReview(options, store, request); }},
      {"GET", "/",
       [options](const http::Request&) {
         auto page = http::pageResponse(options.web_root, "index.html");
         if (!page) throw http::HttpError(404, "the review page is missing; install rockbake again");
         return *page;
       }},
      // The library's files: fileUnder keeps every answer inside OUT (no parent
      // steps, encoded or not, and no link that leads out); a planted page is a download.
      http::libraryFilesRoute(R"(/files/(.+))", out),
      http::staticRoute(R"(/(review\.css|review\.js))", options.web_root),
      http::staticRoute(R"(/vendor/three/((build|examples/jsm)/.+))", options.three_root),
  };
}

int runReview(const ReviewOptions& options) {
  requirePage(options);
  // A folder without a library is the user's to fix (exit status 2), before anything listens.
  if (!fs::is_regular_file(options.library_dir / "index.json"))
    throw InputError({(options.library_dir / "index.json").string()}, "",
                     "not found, and no baked asset folder to index: review serves a library or a folder of bakes",
                     "bake into it first with `rockbake library LIBRARY.yaml -o " + options.library_dir.string() +
                         "` or `rockbake bake PRESET -o " + options.library_dir.string() + "`");
  libraryIndexAssets(options.library_dir);
  http::StopSignals signals;  // first: every thread from here on inherits the blocked mask
  ReviewStore store(options.library_dir);
  http::LocalServer server(reviewRoutes(options, store));
  http::serveUntilStopped(signals, server, {"review", options.host, options.port, options.library_dir.string()});
  return 0;
}

}  // namespace rockbake
