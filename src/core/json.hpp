// JSON outputs (`run`, `analyze`, `theory --json`) are built as nlohmann::json objects, never as
// text: keys keep the order they are set in, numbers are written as the shortest decimal that reads
// back as the same double (at most 17 significant digits), NaN and infinities as null.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace granwave {

using Json = nlohmann::ordered_json;

// One line and a newline. Bytes that are not UTF-8 (a path, a case name) become U+FFFD rather
// than an exception.
inline std::string json_text(const Json& j) {
  return j.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace granwave
