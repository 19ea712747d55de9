#include "procs/rg_kernel/state_store.h"

#include <fcntl.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "persist/atomic_file.h"
#include "persist/exclusive_file.h"

namespace rgnav::rg_kernel {

namespace fs = std::filesystem;

namespace {

// "<prefix>.<G>.<suffix>" -> G, or -1.
int64_t generation_of(const std::string& name, const std::string& prefix, const std::string& suffix)
{
  if (name.size() <= prefix.size() + suffix.size() + 2 || name.compare(0, prefix.size() + 1, prefix + ".") != 0) return -1;
  if (name.compare(name.size() - suffix.size() - 1, std::string::npos, "." + suffix) != 0) return -1;
  const std::string digits = name.substr(prefix.size() + 1, name.size() - prefix.size() - suffix.size() - 2);
  if (digits.empty() || digits.size() > 15 || !std::all_of(digits.begin(), digits.end(), ::isdigit)) return -1;
  return std::stoll(digits);
}

// A new file's name must reach the disk before records in it are called durable.
void sync_dir(const std::string& dir)
{
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(dir + ": cannot open folder: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw std::runtime_error(dir + ": folder fsync failed");
}

std::string numbered(const std::string& dir, const char* prefix, int64_t g, const char* suffix)
{
  char name[96];
  std::snprintf(name, sizeof name, "%s.%010lld.%s", prefix, static_cast<long long>(g), suffix);
  return dir + "/" + name;
}

}  // namespace

StateStore::StateStore(StoreOptions options) : options_(std::move(options))
{
  fs::create_directories(options_.dir);
  const std::string lock = options_.dir + "/state.lock";
  // One kernel per folder: a previous instance that is still dying must not write while this
  // one reads, rotates or deletes.
  lock_fd_ = persist::open_exclusive(lock, "", options_.dir + ": state folder is locked by another live rg_kernel");
  // A snapshot whose writer was killed before its rename is only a temp file: never valid.
  for (const auto& e : fs::directory_iterator(options_.dir))
    if (e.path().extension() == ".tmp") fs::remove(e.path());
  // The single journal of earlier versions is generation 0 (no snapshot before it).
  const std::string legacy = options_.dir + "/inputs.journal";
  if (fs::exists(legacy) && generations("journal").empty() && generations("snapshot").empty()) {
    fs::rename(legacy, journal_path(0));
    spdlog::info("{}: single journal of an earlier version taken as generation 0", options_.dir);
  }
}

StateStore::~StateStore()
{
  if (writer_.joinable()) writer_.join();
  if (journal_ && unsynced_ > 0) {
    try {
      journal_->sync();
    } catch (const std::exception& e) {
      spdlog::error("{}", e.what());
    }
  }
  journal_.reset();
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

std::string StateStore::snapshot_path(int64_t g) const { return numbered(options_.dir, "kernel", g, "snapshot"); }
std::string StateStore::journal_path(int64_t g) const { return numbered(options_.dir, "inputs", g, "journal"); }

std::vector<int64_t> StateStore::generations(const std::string& kind) const
{
  const std::string prefix = kind == "journal" ? "inputs" : "kernel";
  std::vector<int64_t> out;
  for (const auto& e : fs::directory_iterator(options_.dir)) {
    const int64_t g = generation_of(e.path().filename().string(), prefix, kind);
    if (g >= 0) out.push_back(g);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<int64_t> StateStore::snapshot_generations() const
{
  auto g = generations("snapshot");
  std::reverse(g.begin(), g.end());
  return g;
}

std::string StateStore::read_snapshot(int64_t g) const
{
  auto payload = persist::read_checked(snapshot_path(g));
  if (!payload) throw persist::CorruptFile(snapshot_path(g) + ": vanished");
  return std::move(*payload);
}

void StateStore::set_aside(int64_t g, const std::string& why)
{
  problems_.push_back(why);
  std::error_code ec;
  fs::rename(snapshot_path(g), snapshot_path(g) + ".corrupt", ec);
}

std::vector<persist::JournalRecord> StateStore::open_from(int64_t g)
{
  const auto journals = generations("journal");
  if (g == 0 && journals.empty()) {
    journal_ = std::make_unique<persist::Journal>(journal_path(0), false);
    sync_dir(options_.dir);
    generation_ = 0;
    return {};
  }
  // Journals from g on must be contiguous; an older one missing where it is needed is a loss
  // that no restart can repair: refuse rather than build a different map.
  const int64_t newest = journals.empty() ? g : std::max(g, journals.back());
  for (int64_t k = g; k <= newest; ++k)
    if (!fs::exists(journal_path(k)) && !(k == g && g == newest && g > 0))   // a snapshot with no journal yet: fine
      throw std::runtime_error(options_.dir + ": journal generation " + std::to_string(k) +
                               " is missing; the state cannot be rebuilt (move the folder aside to start a new map)");
  std::vector<persist::JournalRecord> records;
  int64_t k = g;
  for (; k <= newest; ++k) {
    auto j = std::make_unique<persist::Journal>(journal_path(k), false);
    records.insert(records.end(), j->recovered().begin(), j->recovered().end());
    if (!j->damage().empty() && k == newest && j->corrupt()) {
      // Bytes that were never records (a file of another kind, a disk fault): no torn write,
      // a loss to report as one. The journal keeps what was intact; a copy as found is kept.
      problems_.push_back(journal_path(k) + ": " + j->damage() + " (the damaged tail was cut off)");
    } else if (!j->damage().empty() && k == newest) {
      // The newest journal torn at its end: what a kill in the middle of a write leaves.
      tail_damage_ = journal_path(k) + ": " + j->damage() + " (the torn tail was cut off)";
    } else if (!j->damage().empty()) {
      // An older journal damaged (it was synced before its successor began: the disk, not a
      // kill). Inputs after the damage cannot be applied without the lost ones.
      problems_.push_back(journal_path(k) + ": " + j->damage() + " (the damaged tail was cut off)");
      for (int64_t later = k + 1; later <= newest; ++later) {
        std::error_code ec;
        fs::rename(journal_path(later), journal_path(later) + ".orphaned", ec);
        problems_.push_back(journal_path(later) + ": follows a damaged journal, not replayed (renamed *.orphaned)");
      }
      journal_ = std::move(j);
      break;
    }
    journal_ = std::move(j);
  }
  generation_ = std::min(k, newest);
  since_snapshot_ = static_cast<int64_t>(records.size());
  sync_dir(options_.dir);   // renames and a journal created just now
  return records;
}

void StateStore::append(uint32_t tag, const std::string& bytes)
{
  journal_->append(tag, bytes);
  if (unsynced_++ == 0) oldest_unsynced_ = std::chrono::steady_clock::now();
  ++since_snapshot_;
  if (unsynced_ >= options_.sync_every_records) sync();
  else sync_if_due();
}

void StateStore::sync()
{
  if (unsynced_ == 0) return;
  journal_->sync();
  unsynced_ = 0;
}

void StateStore::sync_if_due()
{
  if (unsynced_ > 0 && std::chrono::steady_clock::now() - oldest_unsynced_ >= options_.sync_every) sync();
}

bool StateStore::snapshot_due() const
{
  return options_.snapshot_every_records > 0 && since_snapshot_ >= options_.snapshot_every_records && !writing_;
}

int64_t StateStore::start_snapshot(std::string payload)
{
  if (writer_.joinable()) writer_.join();
  // The inputs so far are all in journals < g: close that chain durably, start journal g.
  sync();
  const int64_t g = generation_ + 1;
  journal_ = std::make_unique<persist::Journal>(journal_path(g), false);
  sync_dir(options_.dir);
  generation_ = g;
  since_snapshot_ = 0;
  writing_ = true;
  writer_ = std::thread([this, g, payload = std::move(payload)] {
    try {
      persist::write_atomically(snapshot_path(g), payload);
      remove_old(g);
      std::lock_guard<std::mutex> lock(error_mutex_);
      writer_error_.clear();
    } catch (const std::exception& e) {
      // Nothing is lost: the previous snapshot and every journal since it are still there.
      std::lock_guard<std::mutex> lock(error_mutex_);
      writer_error_ = e.what();
    }
    writing_ = false;
  });
  return g;
}

void StateStore::wait_snapshot()
{
  if (writer_.joinable()) writer_.join();
  const std::string e = last_snapshot_error();
  if (!e.empty()) throw std::runtime_error(e);
}

std::string StateStore::last_snapshot_error() const
{
  std::lock_guard<std::mutex> lock(error_mutex_);
  return writer_error_;
}

void StateStore::remove_old(int64_t newest)
{
  // Keep `newest`, the snapshot before it (the fallback) and every journal since that one.
  int64_t previous = 0;
  for (const int64_t g : generations("snapshot"))
    if (g < newest) previous = std::max(previous, g);
  std::error_code ec;
  for (const int64_t g : generations("snapshot"))
    if (g < previous) fs::remove(snapshot_path(g), ec);
  for (const int64_t g : generations("journal"))
    if (g < previous) fs::remove(journal_path(g), ec);
}

}  // namespace rgnav::rg_kernel
