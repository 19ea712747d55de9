// JSON documents in atomic files that JSON readers open as they are (python -m json.tool, jq, a
// browser) and that still say when they are damaged: the integrity check is the document's first
// member, a fixed-width string "crc32=XXXXXXXX length=NNNNNNNNNN" over the bytes that follow it.
// A truncated or corrupted file fails the check (or the JSON parse) and is refused by name.
// Files in the older framing (atomic_file.h: a header line before the JSON) are still read.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace rgnav::persist {

// The member that carries the check; readers see documents without it.
constexpr const char* kIntegrityKey = "integrity";

// Writes `document` (a non-empty object; an "integrity" member in it is replaced) atomically as
// write_atomically does. Throws std::invalid_argument for a document that is no such object,
// std::runtime_error on I/O failure (the old file is then untouched).
void write_json_atomically(const std::string& path, nlohmann::json document, int indent = 1);

// The document without its integrity member, or nothing if the file does not exist. Throws
// CorruptFile naming the file and the defect (check failed, not JSON, no check).
std::optional<nlohmann::json> read_checked_json(const std::string& path);

// The same, of a file's whole text (for tests and tools that hold it already).
nlohmann::json parse_checked_json(const std::string& text, const std::string& path);

}  // namespace rgnav::persist
