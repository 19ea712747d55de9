#include "persist/journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "persist/atomic_file.h"
#include "persist/exclusive_file.h"

namespace rgnav::persist {
namespace {

constexpr uint32_t kRecordMagic = 0x52474a31;  // "RGJ1"
constexpr size_t kHeader = 16;                 // magic, tag, length, crc32
constexpr uint32_t kMaxRecord = 64u << 20;

void put32(std::string* s, uint32_t v)
{
  for (int i = 0; i < 4; ++i) s->push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
uint32_t get32(const std::string& s, size_t at)
{
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(static_cast<uint8_t>(s[at + i])) << (8 * i);
  return v;
}

}  // namespace

Journal::Journal(std::string path, bool fsync_each) : path_(std::move(path)), fsync_each_(fsync_each)
{
  const auto p = std::filesystem::path(path_);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  // One writer only: a previous instance that is still dying (SIGSTOP, then SIGTERM/SIGKILL
  // from the supervisor) must not append while this one reads and truncates.
  fd_ = open_exclusive(path_, " journal", path_ + ": journal is locked by another live instance");
  std::string data;
  {
    char buf[65536];
    off_t off = 0;
    for (;;) {
      const ssize_t n = ::pread(fd_, buf, sizeof buf, off);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      data.append(buf, static_cast<size_t>(n));
      off += n;
    }
  }
  size_t pos = 0;
  while (pos < data.size()) {
    if (data.size() - pos < kHeader) {
      damage_ = "torn record header at byte " + std::to_string(pos);
      break;
    }
    const uint32_t magic = get32(data, pos), tag = get32(data, pos + 4), len = get32(data, pos + 8), crc = get32(data, pos + 12);
    if (magic != kRecordMagic || len > kMaxRecord) {
      damage_ = "bad record header at byte " + std::to_string(pos);
      corrupt_ = true;
      break;
    }
    if (data.size() - pos - kHeader < len) {
      damage_ = "torn record at byte " + std::to_string(pos);
      break;
    }
    std::string bytes = data.substr(pos + kHeader, len);
    if (crc32_of(bytes) != crc) {
      damage_ = "CRC mismatch in record at byte " + std::to_string(pos);
      corrupt_ = true;
      break;
    }
    recovered_.push_back({tag, std::move(bytes)});
    pos += kHeader + len;
  }
  // Bytes that were never records are evidence (a disk fault, a file of another kind put here):
  // keep the file as found before cutting them off.
  if (corrupt_) {
    const std::string kept = path_ + ".damaged";
    std::ofstream copy(kept, std::ios::binary | std::ios::trunc);
    copy.write(data.data(), static_cast<std::streamsize>(data.size()));
    copy.close();
    damage_ += copy ? " (the file as found is kept as " + kept + ")" : " (no copy could be kept as " + kept + ")";
  }
  // Cut off a damaged tail so new records follow the last good one.
  if (::ftruncate(fd_, static_cast<off_t>(pos)) != 0 || ::lseek(fd_, static_cast<off_t>(pos), SEEK_SET) < 0)
    throw std::runtime_error(path_ + ": cannot truncate damaged tail: " + std::strerror(errno));
  records_ = static_cast<int64_t>(recovered_.size());
}

Journal::~Journal()
{
  if (fd_ >= 0) ::close(fd_);
}

void Journal::append(uint32_t tag, const std::string& bytes)
{
  std::string rec;
  rec.reserve(kHeader + bytes.size());
  put32(&rec, kRecordMagic);
  put32(&rec, tag);
  put32(&rec, static_cast<uint32_t>(bytes.size()));
  put32(&rec, crc32_of(bytes));
  rec += bytes;
  size_t done = 0;
  while (done < rec.size()) {
    const ssize_t n = ::write(fd_, rec.data() + done, rec.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(path_ + ": journal write failed: " + std::strerror(errno));
    done += static_cast<size_t>(n);
  }
  if (fsync_each_ && ::fdatasync(fd_) != 0) throw std::runtime_error(path_ + ": fdatasync failed: " + std::strerror(errno));
  ++records_;
}

void Journal::sync()
{
  if (::fdatasync(fd_) != 0) throw std::runtime_error(path_ + ": fdatasync failed: " + std::strerror(errno));
}

void Journal::reset()
{
  if (::ftruncate(fd_, 0) != 0 || ::lseek(fd_, 0, SEEK_SET) < 0) throw std::runtime_error(path_ + ": cannot reset journal");
  if (fsync_each_) ::fdatasync(fd_);
  records_ = 0;
}

}  // namespace rgnav::persist
