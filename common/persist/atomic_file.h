// Files that are either entirely the old version or entirely the new one, and that say so when
// they are neither. write_atomically: temp file, fsync, rename over the target, fsync of the
// folder. The payload is framed by a header line holding its length and CRC-32, so a truncated
// or corrupted file is detected on read instead of being half-loaded.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

namespace rgnav::persist {

class CorruptFile : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

// Throws std::runtime_error on I/O failure (the old file is then untouched).
void write_atomically(const std::string& path, const std::string& payload);
// The same without the header line: `bytes` carry their own check (checked_json.h).
void write_atomically_raw(const std::string& path, const std::string& bytes);
// Nothing if the file does not exist; throws CorruptFile (naming the file and the defect) if
// the header, length or CRC do not match.
std::optional<std::string> read_checked(const std::string& path);
// The payload of a file's whole text in this framing; throws CorruptFile naming `path`.
std::string check_framed(const std::string& text, const std::string& path);

uint32_t crc32_of(const std::string& bytes);

}  // namespace rgnav::persist
