#include "telegram_parser.h"

#include "crc16.h"

namespace rgnav::drivers::sick {

TelegramParser::TelegramParser(uint8_t expected_address, size_t max_payload)
    : expected_address_(expected_address), max_payload_(max_payload)
{
}

void TelegramParser::reset()
{
  buf_start_ += buf_.size();
  buf_.clear();
  chunks_.clear();
  in_garbage_ = false;
}

void TelegramParser::drop_front(size_t n)
{
  buf_.erase(buf_.begin(), buf_.begin() + static_cast<long>(n));
  buf_start_ += n;
  while (!chunks_.empty() && chunks_.front().end <= buf_start_) chunks_.pop_front();
}

const TelegramParser::Chunk* TelegramParser::chunk_of(uint64_t absolute_offset) const
{
  for (const auto& c : chunks_)
    if (absolute_offset < c.end) return &c;
  return chunks_.empty() ? nullptr : &chunks_.back();
}

ParseOutput TelegramParser::feed(const uint8_t* data, size_t size, int64_t rx_utime)
{
  ParseOutput out;
  if (size > 0) {
    buf_.insert(buf_.end(), data, data + size);
    chunks_.push_back({buf_start_ + buf_.size(), rx_utime});
  }
  size_t pos = 0;  // everything before pos is consumed; erased once at the end
  auto lose_sync = [&] {
    if (!in_garbage_) ++stats_.resyncs;
    in_garbage_ = true;
  };
  while (pos < buf_.size()) {
    const uint8_t b = buf_[pos];
    if (b != kStx) {
      if (b == kAck) {
        ++stats_.acks;
        ++out.acks;
      } else if (b == kNak) {
        ++stats_.naks;
        ++out.naks;
      } else {
        ++stats_.skipped_bytes;
        lose_sync();
      }
      ++pos;
      continue;
    }
    const size_t avail = buf_.size() - pos;
    if (avail >= 2 && buf_[pos + 1] != expected_address_) {
      ++stats_.bad_headers;
      ++stats_.skipped_bytes;
      lose_sync();
      ++pos;
      continue;
    }
    if (avail < kHeaderSize) break;
    const size_t len = get_u16(&buf_[pos + 2]);
    if (len == 0 || len > max_payload_) {
      ++stats_.bad_headers;
      ++stats_.skipped_bytes;
      lose_sync();
      ++pos;
      continue;
    }
    const size_t total = framed_size(len);
    if (avail < total) break;
    const uint16_t crc = crc16(&buf_[pos], kHeaderSize + len);
    if (crc != get_u16(&buf_[pos + kHeaderSize + len])) {
      ++stats_.crc_errors;
      ++stats_.skipped_bytes;
      lose_sync();
      ++pos;  // restart one byte later: the real start may lie inside this candidate
      continue;
    }
    ReceivedTelegram rt;
    rt.telegram.address = buf_[pos + 1];
    rt.telegram.payload.assign(buf_.begin() + static_cast<long>(pos + kHeaderSize),
                               buf_.begin() + static_cast<long>(pos + kHeaderSize + len));
    const uint64_t last = buf_start_ + pos + total - 1;
    if (const Chunk* c = chunk_of(last)) {
      rt.rx_utime = c->utime;
      rt.trailing_bytes = static_cast<size_t>(c->end - last - 1);
    }
    out.telegrams.push_back(std::move(rt));
    ++stats_.telegrams;
    in_garbage_ = false;
    pos += total;
  }
  drop_front(pos);
  return out;
}

}  // namespace rgnav::drivers::sick
