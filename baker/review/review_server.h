// `rockbake review OUT` (docs/review.md): a baked library's review page and its
// JSON API on the local HTTP layer (http/local_server.h, with its limits and
// who-may-call rules): GET /api/assets, GET /api/assets/<name>, POST
// /api/review, the library's files under /files/ (only regular files inside
// OUT, no link out of it), the page from `web_root` and the pinned three.js.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "http/route.h"
#include "review/review_store.h"

namespace rockbake {

struct ReviewOptions {
  std::filesystem::path library_dir;  // OUT, holding index.json
  std::string host = "127.0.0.1";     // only this machine unless told otherwise
  int port = 8632;                    // 0: any free port
  std::filesystem::path web_root;     // the page: review/ in rockbake's data folder (platform/data_dir.h)
  std::filesystem::path three_root;   // the pinned three.js: studio/node_modules/three there
};

// The route table; `store` keeps review.json.
std::vector<http::Route> reviewRoutes(const ReviewOptions& options, ReviewStore& store);

// Serves until SIGINT or SIGTERM, then returns 0. Prints `review: http://HOST:PORT/`
// on stdout once it listens. Throws InputError when OUT has no index.json,
// std::runtime_error when it is not an index, the address cannot be bound or
// the page's files are missing.
int runReview(const ReviewOptions& options);

}  // namespace rockbake
