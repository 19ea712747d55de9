// An append-only journal of input records (write-ahead log): a process that owns state
// appends each input before applying it, so that after a SIGKILL at any instant replaying
// the journal rebuilds exactly the state it had. Each record is framed by its length, a tag
// and a CRC-32; a torn or corrupted tail is detected, reported and cut off on open (a corrupted
// one after a copy of the file was kept aside).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rgnav::persist {

struct JournalRecord
{
  uint32_t tag = 0;        // what kind of input (caller-defined)
  std::string bytes;       // the input, e.g. an LCM-encoded message
};

class Journal
{
 public:
  // Opens (creating if needed), takes an exclusive lock (waiting up to 3 s for a dying
  // previous owner; throws std::runtime_error if it stays locked), and reads every intact
  // record; a damaged tail is truncated away and described in damage().
  explicit Journal(std::string path, bool fsync_each = true);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  const std::vector<JournalRecord>& recovered() const { return recovered_; }
  const std::string& damage() const { return damage_; }
  // The damage is no torn end (what a kill in the middle of a write leaves) but bytes that were
  // never a record: a bad header or a CRC mismatch, e.g. a file of another kind. The whole file
  // as found is then kept as <path>.damaged before its tail is cut off (damage() says so).
  bool corrupt() const { return corrupt_; }

  // Throws std::runtime_error if the record cannot be written durably.
  void append(uint32_t tag, const std::string& bytes);
  // Makes every record appended so far durable (fdatasync): for callers that append with
  // fsync_each = false and commit in groups. Throws std::runtime_error on failure.
  void sync();
  // Empties the journal (after a checkpoint made its records redundant).
  void reset();
  int64_t records() const { return records_; }

 private:
  std::string path_;
  bool fsync_each_;
  int fd_ = -1;
  std::vector<JournalRecord> recovered_;
  std::string damage_;
  bool corrupt_ = false;
  int64_t records_ = 0;
};

}  // namespace rgnav::persist
