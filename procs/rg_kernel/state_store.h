// The RG kernel's state folder: snapshots plus a write-ahead journal cut into generations, so
// a restart costs one snapshot load plus a short journal tail, however long the run was.
//
//   kernel.<G>.snapshot   the kernel's complete state after every input of journals < G
//                         (persist::write_atomically: temp file, fsync, rename; length + CRC)
//   inputs.<G>.journal    inputs after snapshot G (persist::Journal: framed, CRC per record)
//   state.lock            flock: one kernel per folder
//
// Generation 0 has no snapshot (the empty map). Taking snapshot G closes journal G-1 and opens
// journal G at once, then writes the snapshot in the background; once it is durable, files
// older than the previous snapshot are deleted. So the newest snapshot, the one before it and
// every journal since the one before it are always on disk: a snapshot found corrupt on start
// is reported, renamed *.corrupt (never loaded) and the previous one is used with the longer
// journal tail — the same inputs, so the same map.
//
// Durability (group commit): records are written at once (a SIGKILL cannot lose them: they are
// in the kernel's page cache, which outlives the process) but fdatasync'ed only every
// sync_every_records records or sync_every after the oldest unsynced one, and whenever the
// owner calls sync() — the kernel does before every publication. What an OS crash or power
// loss can lose is therefore at most that window of inputs, none of which had been published
// (acknowledged) in a map; the scan mapper still has them and republishes on its restart.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "persist/journal.h"

namespace rgnav::rg_kernel {

struct StoreOptions
{
  std::string dir;
  int sync_every_records = 20;                        // group commit: fsync after this many ...
  std::chrono::milliseconds sync_every{100};          // ... or this long after the oldest unsynced
  int64_t snapshot_every_records = 200;               // journal records between snapshots (0: never)
};

class StateStore
{
 public:
  // Locks the folder (waits up to 3 s for a dying previous owner, then throws
  // std::runtime_error), removes stray temp files and moves a legacy `inputs.journal` to
  // generation 0. Nothing is read yet: see newest_snapshots() / open_from().
  explicit StateStore(StoreOptions options);
  ~StateStore();
  StateStore(const StateStore&) = delete;
  StateStore& operator=(const StateStore&) = delete;

  // Generations of the snapshots on disk, newest first.
  std::vector<int64_t> snapshot_generations() const;
  // The checked payload of snapshot g; throws persist::CorruptFile if damaged.
  std::string read_snapshot(int64_t g) const;
  // Renames a damaged snapshot to *.corrupt, so it is kept for inspection but never loaded.
  void set_aside(int64_t g, const std::string& why);

  // Opens journals g, g+1, ... (g: the generation of the snapshot loaded, 0 for none) and
  // returns their records in order; the newest stays open for appending. Throws
  // std::runtime_error if the chain cannot rebuild the state (a journal is missing). A damaged
  // journal that is not the newest ends the replay there; later ones are renamed *.orphaned and
  // the damage is listed in problems(); a torn end of the newest is cut off (tail_damage()),
  // and so is a corrupt one (bytes that were never records), but that is listed in problems().
  std::vector<persist::JournalRecord> open_from(int64_t g);
  // Damage that lost or set aside data (corrupt snapshots, a damaged older journal).
  const std::vector<std::string>& problems() const { return problems_; }
  // A torn record at the end of the newest journal: the normal trace of a kill mid-write.
  const std::string& tail_damage() const { return tail_damage_; }

  void append(uint32_t tag, const std::string& bytes);
  void sync();             // every record appended so far durable now
  void sync_if_due();      // group-commit deadline passed?
  bool unsynced() const { return unsynced_ > 0; }

  // True when enough records went to the journal since the last snapshot and no snapshot is
  // being written.
  bool snapshot_due() const;
  // Starts generation generation()+1 and writes `payload` (the state after every record so
  // far) as its snapshot in the background. Returns the new generation.
  int64_t start_snapshot(std::string payload);
  // Waits for a snapshot being written; rethrows its error (tests, shutdown).
  void wait_snapshot();
  int64_t generation() const { return generation_; }
  int64_t records_since_snapshot() const { return since_snapshot_; }
  // The error of the last background snapshot write, if it failed ("" otherwise).
  std::string last_snapshot_error() const;

  std::string snapshot_path(int64_t g) const;
  std::string journal_path(int64_t g) const;

 private:
  std::vector<int64_t> generations(const std::string& suffix) const;
  void remove_old(int64_t newest_snapshot);

  const StoreOptions options_;
  int lock_fd_ = -1;
  std::unique_ptr<persist::Journal> journal_;
  int64_t generation_ = 0;
  int64_t since_snapshot_ = 0;
  int unsynced_ = 0;
  std::chrono::steady_clock::time_point oldest_unsynced_;
  std::vector<std::string> problems_;
  std::string tail_damage_;
  std::thread writer_;
  std::atomic<bool> writing_{false};
  mutable std::mutex error_mutex_;
  std::string writer_error_;
};

}  // namespace rgnav::rg_kernel
