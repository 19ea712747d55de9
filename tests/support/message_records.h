// One line per message, written by the contract test programs and read by the C++ and Java
// checks:  CHANNEL <TAB> TYPE <TAB> HEX-OF-ENCODED-BYTES <TAB> CANONICAL-JSON
// (JSON from to_json(), which has no tabs or newlines).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rgnav::testing {

struct MessageRecord
{
  std::string channel;
  std::string type;
  std::string hex;
  std::string json;

  bool operator==(const MessageRecord& o) const
  {
    return channel == o.channel && type == o.type && hex == o.hex && json == o.json;
  }
};

std::string to_hex(const uint8_t* data, size_t size);
std::vector<uint8_t> from_hex(const std::string& hex);  // throws std::invalid_argument

std::string format_record(const MessageRecord& r);  // without the newline
// Reads every complete line of a records file (a partially written last line is ignored).
std::vector<MessageRecord> read_records(const std::string& path);

}  // namespace rgnav::testing
