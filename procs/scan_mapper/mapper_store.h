// Durable mapper state, so that nothing the scan mapper published is lost by a SIGKILL: every
// accepted scan (with the pose graph edges added with it) and every change of the estimates
// (loop closure) is appended to a CRC-framed write-ahead journal (persist/journal.h) and made
// durable before it is published; every snapshot_every_records records the whole state is
// written as an atomic snapshot (mapper_state_io.h) and the journal emptied.
//
// Records carry a sequence number and the snapshot the newest one it includes, so a crash
// between writing a snapshot and emptying the journal replays nothing twice. On open, the
// snapshot is loaded and the journal replayed; a torn or corrupt journal tail and a record that
// does not fit the state are reported and dropped (with everything after them), a damaged
// snapshot is moved aside (".corrupt") and the map starts afresh; nothing damaged is loaded.
#pragma once

#include <memory>
#include <string>

#include "persist/journal.h"
#include "scan_mapper/mapper_state_io.h"

namespace rgnav::persist {
class ByteWriter;
}

namespace rgnav::scan_mapper {

struct StoreOptions
{
  std::string snapshot_path;        // journal: snapshot_path + ".journal"
  bool resume = true;               // false: discard what is stored and start afresh
  int snapshot_every_records = 100; // journal records between snapshots
  bool fsync_each_record = true;
};

struct RecoveryReport
{
  size_t scans = 0;              // scans in the recovered state (0 = fresh origin)
  size_t edges = 0;
  size_t snapshot_scans = 0;     // ... of which from the snapshot
  size_t records_replayed = 0;   // journal records applied on top
  std::string damage;            // what was wrong and dropped ("" = nothing)
};

class MapperStore
{
 public:
  // Takes the journal's lock (throws std::runtime_error if another live instance holds it),
  // recovers and, if anything was replayed or dropped, compacts into a new snapshot.
  explicit MapperStore(StoreOptions options);

  const RecoveryReport& report() const { return report_; }
  // The recovered state (once; empty when starting at a fresh origin).
  PersistedState take_recovered() { return std::move(recovered_); }

  // Journals node `index` of the mapper (just accepted) with the edges added since the last
  // record; durable when it returns. Throws std::runtime_error if it cannot be made durable.
  void record_scan(const ScanMapper& mapper, int index, const ScanIdState& ids);
  // Journals the current estimates of all nodes and the new edges (after a loop closure).
  void record_estimates(const ScanMapper& mapper, const ScanIdState& ids);
  // Writes a snapshot and empties the journal (also done every snapshot_every_records).
  void snapshot(const ScanMapper& mapper, const ScanIdState& ids);

  int64_t journal_records() const { return journal_->records(); }

 private:
  void recover();
  void append(uint32_t tag, const std::string& bytes, const ScanMapper& mapper, const ScanIdState& ids);
  void write_new_edges(persist::ByteWriter& w, const ScanMapper& mapper);

  StoreOptions options_;
  std::unique_ptr<persist::Journal> journal_;
  RecoveryReport report_;
  PersistedState recovered_;
  uint64_t seq_ = 0;             // sequence number of the newest record
  size_t edges_recorded_ = 0;    // graph edges already in the snapshot or journal
};

}  // namespace rgnav::scan_mapper
