#include "message_records.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rgnav::testing {

std::string to_hex(const uint8_t* data, size_t size)
{
  static const char* digits = "0123456789abcdef";
  std::string out(2 * size, '0');
  for (size_t i = 0; i < size; ++i) {
    out[2 * i] = digits[data[i] >> 4];
    out[2 * i + 1] = digits[data[i] & 15];
  }
  return out;
}

std::vector<uint8_t> from_hex(const std::string& hex)
{
  if (hex.size() % 2) throw std::invalid_argument("odd hex length");
  auto nibble = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    throw std::invalid_argument("not a hex digit");
  };
  std::vector<uint8_t> out(hex.size() / 2);
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = static_cast<uint8_t>(nibble(hex[2 * i]) << 4 | nibble(hex[2 * i + 1]));
  return out;
}

std::string format_record(const MessageRecord& r)
{
  return r.channel + "\t" + r.type + "\t" + r.hex + "\t" + r.json;
}

std::vector<MessageRecord> read_records(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<MessageRecord> out;
  size_t start = 0;
  for (size_t nl = text.find('\n'); nl != std::string::npos; start = nl + 1, nl = text.find('\n', start)) {
    const std::string line = text.substr(start, nl - start);
    std::vector<std::string> parts;
    std::stringstream ss(line);
    for (std::string p; std::getline(ss, p, '\t');) parts.push_back(p);
    if (parts.size() != 4) throw std::invalid_argument(path + ": malformed record line: " + line.substr(0, 80));
    out.push_back({parts[0], parts[1], parts[2], parts[3]});
  }
  return out;
}

}  // namespace rgnav::testing
