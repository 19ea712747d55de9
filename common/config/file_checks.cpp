#include "config/file_checks.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "config/config.h"

namespace rgnav::config {

namespace {

// The whole file; throws ConfigError when it cannot be opened or holds no bytes.
std::string read_bytes(const std::string& path, const std::string& what)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot open " + what + " file");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw ConfigError(path + ": cannot read " + what + " file");
  std::string bytes = s.str();
  if (bytes.empty()) throw ConfigError(path + ": empty " + what + " file");
  return bytes;
}

bool all_space(const std::string& text)
{
  for (const char c : text)
    if (!std::isspace(static_cast<unsigned char>(c))) return false;
  return true;
}

// Binary PGM/PPM (P5, P6): header "P5 <w> <h> <maxval>" with comments, one white space, then
// w * h * channels * (1 or 2) bytes. False when the header cannot be read (the decoder judges).
bool pnm_payload(const std::string& b, size_t* header_end, size_t* payload)
{
  if (b.size() < 3 || b[0] != 'P' || (b[1] != '5' && b[1] != '6')) return false;
  size_t at = 2;
  long long v[3] = {0, 0, 0};
  for (long long& x : v) {
    for (;;) {
      while (at < b.size() && std::isspace(static_cast<unsigned char>(b[at]))) ++at;
      if (at < b.size() && b[at] == '#') {
        while (at < b.size() && b[at] != '\n') ++at;
        continue;
      }
      break;
    }
    if (at >= b.size() || !std::isdigit(static_cast<unsigned char>(b[at]))) return false;
    while (at < b.size() && std::isdigit(static_cast<unsigned char>(b[at])) && x < (1LL << 40)) x = 10 * x + (b[at++] - '0');
  }
  if (at >= b.size() || v[0] <= 0 || v[1] <= 0 || v[2] <= 0 || v[2] > 65535) return false;
  *header_end = at + 1;   // the single white space after maxval
  *payload = static_cast<size_t>(v[0] * v[1] * (b[1] == '6' ? 3 : 1) * (v[2] > 255 ? 2 : 1));
  return true;
}

}  // namespace

std::string binary_defect(const std::string& t)
{
  size_t i = 0;
  while (i < t.size()) {
    const auto c = static_cast<unsigned char>(t[i]);
    if (c == 0) return "NUL byte at byte " + std::to_string(i);
    size_t more = 0;
    if (c < 0x80) more = 0;
    else if ((c & 0xe0) == 0xc0 && c >= 0xc2) more = 1;
    else if ((c & 0xf0) == 0xe0) more = 2;
    else if ((c & 0xf8) == 0xf0 && c <= 0xf4) more = 3;
    else return "invalid UTF-8 at byte " + std::to_string(i);
    if (i + more >= t.size() && more > 0) return "invalid UTF-8 at byte " + std::to_string(i);   // cut mid-character
    for (size_t k = 1; k <= more; ++k)
      if ((static_cast<unsigned char>(t[i + k]) & 0xc0) != 0x80) return "invalid UTF-8 at byte " + std::to_string(i);
    i += more + 1;
  }
  return "";
}

std::string read_text_file(const std::string& path, const std::string& what)
{
  std::string text = read_bytes(path, what);
  if (all_space(text)) throw ConfigError(path + ": empty " + what + " file (white space only)");
  const std::string defect = binary_defect(text);
  if (!defect.empty()) throw ConfigError(path + ": not a " + what + " file (binary data: " + defect + ")");
  return text;
}

std::string read_image_file(const std::string& path, const std::string& what)
{
  std::string b = read_bytes(path, what);
  const auto cut = [&](const std::string& why) { return ConfigError(path + ": " + what + " is cut off (" + why + ")"); };
  static const std::string kPng("\x89PNG\r\n\x1a\n", 8);
  if (b.compare(0, kPng.size(), kPng) == 0) {
    // The last chunk: length 0, "IEND", CRC.
    if (b.size() < kPng.size() + 12 || b.compare(b.size() - 8, 4, "IEND") != 0) throw cut("PNG without its IEND chunk");
    return b;
  }
  if (b.size() >= 2 && static_cast<unsigned char>(b[0]) == 0xff && static_cast<unsigned char>(b[1]) == 0xd8) {
    // End-of-image marker FF D9; some writers pad after it.
    const size_t from = b.size() > 64 ? b.size() - 64 : 2;
    if (b.find("\xff\xd9", from) == std::string::npos) throw cut("JPEG without its end-of-image marker");
    return b;
  }
  size_t header_end = 0, payload = 0;
  if (pnm_payload(b, &header_end, &payload) && b.size() < header_end + payload)
    throw cut(std::to_string(b.size() - std::min(b.size(), header_end)) + " pixel bytes, the header says " +
              std::to_string(payload));
  return b;
}

}  // namespace rgnav::config
