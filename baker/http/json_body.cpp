#include "http/json_body.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace rockbake::http {

using nlohmann::json;

json parseJsonBody(const Request& request, int max_depth) {
  const json::parser_callback_t depth = [max_depth](int level, json::parse_event_t event, json&) {
    if (level >= max_depth && (event == json::parse_event_t::object_start || event == json::parse_event_t::array_start))
      throw HttpError(400, fmt::format("the request body nests deeper than {} levels", max_depth));
    return true;
  };
  try {
    return json::parse(request.body, depth);
  } catch (const json::parse_error& e) {
    throw HttpError(400, fmt::format("the request body is not valid JSON (at byte {} of {}); send a JSON value", e.byte,
                                     request.body.size()));
  }
}

const json& member(const json& object, const std::string& key, const std::string& shape) {
  if (!object.is_object()) throw HttpError(400, "expected " + shape);
  const auto it = object.find(key);
  if (it == object.end()) throw HttpError(400, key + ": missing; expected " + shape);
  return *it;
}

std::string stringMember(const json& object, const std::string& key, const std::string& shape) {
  const json& value = member(object, key, shape);
  if (!value.is_string()) throw HttpError(400, key + ": expected a string; expected " + shape);
  return value.get<std::string>();
}

bool boolMember(const json& object, const std::string& key, bool fallback) {
  if (!object.is_object() || !object.contains(key)) return fallback;
  const json& value = object.at(key);
  if (!value.is_boolean()) throw HttpError(400, key + ": expected true or false");
  return value.get<bool>();
}

double numberValue(const json& value, const std::string& key, const std::string& what) {
  if (!value.is_number() || !std::isfinite(value.get<double>())) throw HttpError(400, key + ": expected " + what);
  return value.get<double>();
}

Response jsonResponse(const json& value, int status) {
  Response response;
  response.status = status;
  response.body = value.dump(-1, ' ', false, json::error_handler_t::replace);
  return response;
}

Response errorResponse(int status, const std::string& message) {
  return jsonResponse({{"error", escapeControlBytes(message)}}, status);
}

}  // namespace rockbake::http
