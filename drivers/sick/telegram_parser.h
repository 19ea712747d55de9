// Streaming telegram parser: feed it bytes in whatever chunks the port delivers; it returns
// the complete telegrams with a good CRC. It never trusts the stream:
//  - bytes before an STX are skipped (counted as one resync per run of garbage); lone ACK /
//    NAK bytes between telegrams are reported as such;
//  - a candidate start whose address is not the expected one or whose length is 0 or above
//    the bound is rejected at once (an oversize length never makes it wait for kilobytes);
//  - a candidate whose CRC fails is dropped and counted; parsing then restarts one byte after
//    that STX, so a real telegram hidden inside a false start is still found.
// Each telegram carries the receive time of the chunk holding its last byte, which the
// driver uses to estimate when the scan was measured.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "telegram.h"

namespace rgnav::drivers::sick {

struct ParserStats
{
  uint64_t telegrams = 0;       // accepted (good CRC)
  uint64_t crc_errors = 0;      // complete candidates with a wrong CRC
  uint64_t bad_headers = 0;     // STX followed by a wrong address or impossible length
  uint64_t resyncs = 0;         // times the parser lost sync (garbage run, bad header, bad CRC)
  uint64_t skipped_bytes = 0;   // bytes thrown away while searching for a start
  uint64_t acks = 0;
  uint64_t naks = 0;
};

struct ReceivedTelegram
{
  Telegram telegram;
  int64_t rx_utime = 0;       // receive time of the chunk holding its last byte
  size_t trailing_bytes = 0;  // bytes of that chunk after its last byte (they came later)
};

struct ParseOutput
{
  std::vector<ReceivedTelegram> telegrams;
  int acks = 0;
  int naks = 0;
};

class TelegramParser
{
 public:
  // expected_address: kAddressHost on the host side, kAddressLms on the device side.
  explicit TelegramParser(uint8_t expected_address, size_t max_payload = kMaxPayload);

  ParseOutput feed(const uint8_t* data, size_t size, int64_t rx_utime = 0);
  void reset();  // forget buffered bytes (port reopened, baud changed)

  const ParserStats& stats() const { return stats_; }
  size_t buffered() const { return buf_.size(); }

 private:
  struct Chunk
  {
    uint64_t end;  // absolute stream offset one past the chunk's last byte
    int64_t utime;
  };
  void drop_front(size_t n);
  // The chunk holding the byte at this absolute stream offset.
  const Chunk* chunk_of(uint64_t absolute_offset) const;

  const uint8_t expected_address_;
  const size_t max_payload_;
  std::vector<uint8_t> buf_;
  uint64_t buf_start_ = 0;  // absolute offset of buf_[0]
  std::deque<Chunk> chunks_;
  bool in_garbage_ = false;
  ParserStats stats_;
};

}  // namespace rgnav::drivers::sick
