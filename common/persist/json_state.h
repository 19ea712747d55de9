// A process's saved state as one JSON document in an atomic checked file (checked_json.h): the
// document carries its schema name and version, so that a file of another kind or version is
// refused rather than misread.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace rgnav::persist {

// Writes `body` (an object) with "schema" and "schema_version" added; creates the folder.
void write_json_state(const std::string& path, const std::string& schema, int version, nlohmann::json body);

// The document, or nullopt when there is no file. Throws std::runtime_error naming the file for
// a damaged file or one of another schema or version ("PATH: not WHAT state: ..."); the
// document's own fields are the caller's to check (wrap a failure with not_this_state).
std::optional<nlohmann::json> read_json_state(const std::string& path, const std::string& schema, int version,
                                              const std::string& what);

// "PATH: not a WHAT state: WHY", for a document whose fields are wrong.
std::runtime_error not_this_state(const std::string& path, const std::string& what, const std::exception& why);

}  // namespace rgnav::persist
