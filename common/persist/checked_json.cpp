#include "persist/checked_json.h"

#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "persist/atomic_file.h"

namespace rgnav::persist {
namespace {

// `{"integrity": "crc32=%08x length=%010zu",` — fixed width, so the checked bytes start at a known
// offset and the check covers everything after it, the closing brace included.
constexpr const char* kLead = "{\"integrity\": \"crc32=";
constexpr size_t kPrefixSize = 21 + 8 + 8 + 10 + 2;  // lead, crc hex, " length=", digits, `",`
constexpr const char* kLegacyMagic = "rgnav-checked-file v1";

std::string prefix_for(const std::string& rest)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%scrc32=%08" PRIx32 " length=%010zu\",", "{\"integrity\": \"",
                crc32_of(rest), rest.size());
  return buf;
}

}  // namespace

void write_json_atomically(const std::string& path, nlohmann::json document, int indent)
{
  if (!document.is_object()) throw std::invalid_argument(path + ": a checked JSON file holds an object");
  document.erase(kIntegrityKey);
  if (document.empty()) throw std::invalid_argument(path + ": a checked JSON file holds a non-empty object");
  const std::string body = document.dump(indent);  // "{...}": the members follow its first byte
  const std::string rest = body.substr(1);
  write_atomically_raw(path, prefix_for(rest) + rest);
}

nlohmann::json parse_checked_json(const std::string& text, const std::string& path)
{
  if (text.empty()) throw CorruptFile(path + ": empty file");
  if (text.compare(0, std::char_traits<char>::length(kLegacyMagic), kLegacyMagic) == 0) {
    // The older framing: a header line, then the JSON (files written before this form).
    const auto payload = check_framed(text, path);
    try {
      return nlohmann::json::parse(payload);
    } catch (const std::exception& e) {
      throw CorruptFile(path + ": not JSON: " + e.what());
    }
  }
  if (text.size() < kPrefixSize || text.compare(0, std::char_traits<char>::length(kLead), kLead) != 0)
    throw CorruptFile(path + ": not a checked JSON file (no integrity member first)");
  unsigned crc = 0;
  size_t length = 0;
  if (std::sscanf(text.c_str() + std::char_traits<char>::length(kLead), "%8x length=%10zu\",", &crc, &length) != 2)
    throw CorruptFile(path + ": not a checked JSON file (bad integrity member)");
  const std::string rest = text.substr(kPrefixSize);
  if (rest.size() != length)
    throw CorruptFile(path + ": truncated or padded: " + std::to_string(rest.size()) + " bytes, integrity says " +
                      std::to_string(length));
  if (crc32_of(rest) != crc || prefix_for(rest) != text.substr(0, kPrefixSize))
    throw CorruptFile(path + ": CRC mismatch (corrupted)");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const std::exception& e) {
    throw CorruptFile(path + ": not JSON: " + e.what());
  }
  j.erase(kIntegrityKey);
  return j;
}

std::optional<nlohmann::json> read_checked_json(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_checked_json(ss.str(), path);
}

}  // namespace rgnav::persist
