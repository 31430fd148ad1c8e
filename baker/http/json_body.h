// JSON in and out of a local server's routes (docs/studio.md, "The server's
// promises"):
//   - parseJsonBody reads a request body nested at most kMaxJsonDepth levels,
//     checked while it is parsed (nlohmann's parser callback), so a body of
//     100 000 brackets is refused long before any recursion could overflow a
//     stack; errors name the byte offset and never echo the body (HttpError 400);
//   - the member getters check each value's type and say which key was wrong
//     (HttpError 400), so no library type error reaches the client;
//   - jsonResponse writes invalid UTF-8 in strings as U+FFFD instead of failing,
//     errorResponse escapes control bytes: a message may quote what the client sent.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "http/route.h"

namespace rockbake::http {

inline constexpr int kMaxJsonDepth = 64;

nlohmann::json parseJsonBody(const Request& request, int max_depth = kMaxJsonDepth);

// The member `key` of a JSON object: HttpError 400 when `object` is not an
// object or lacks it ("expected {...}" is `shape`, the body's expected form).
const nlohmann::json& member(const nlohmann::json& object, const std::string& key, const std::string& shape);
std::string stringMember(const nlohmann::json& object, const std::string& key, const std::string& shape);
// `fallback` when absent; HttpError 400 when present and not true or false.
bool boolMember(const nlohmann::json& object, const std::string& key, bool fallback);
// A finite number; HttpError 400 naming `what` it should be otherwise.
double numberValue(const nlohmann::json& value, const std::string& key, const std::string& what);

Response jsonResponse(const nlohmann::json& value, int status = 200);
Response errorResponse(int status, const std::string& message);

}  // namespace rockbake::http
