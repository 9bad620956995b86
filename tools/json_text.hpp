#pragma once
/// JSON text for a file or a message. Linux names are bytes, so a path echoed in a report (the
/// grammar, the output folder) need not be UTF-8; nlohmann's dump throws on such a string, which
/// ended a whole run at its report with "[json.exception.type_error.316] invalid UTF-8 byte". Here
/// a byte that is not UTF-8 is written as U+FFFD instead.
#include <nlohmann/json.hpp>

#include <string>

namespace canopy::cli {

template <typename Json>
std::string json_text(const Json& j, int indent = -1) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace canopy::cli
