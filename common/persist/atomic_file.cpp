#include "persist/atomic_file.h"

#include <algorithm>

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rgnav::persist {
namespace {

constexpr const char* kMagic = "rgnav-checked-file v1";

void write_all(int fd, const std::string& data, const std::string& path)
{
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
    done += static_cast<size_t>(n);
  }
}

}  // namespace

uint32_t crc32_of(const std::string& bytes)
{
  return static_cast<uint32_t>(::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

void write_atomically_raw(const std::string& path, const std::string& bytes)
{
  const std::filesystem::path target(path);
  const auto dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  std::filesystem::create_directories(dir);
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(tmp + ": cannot create: " + std::strerror(errno));
  try {
    write_all(fd, bytes, tmp);
    if (::fsync(fd) != 0) throw std::runtime_error(tmp + ": fsync failed: " + std::strerror(errno));
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  ::close(fd);
  if (::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error(path + ": rename failed: " + std::strerror(errno));
  // The rename itself must reach the disk: fsync the folder.
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

void write_atomically(const std::string& path, const std::string& payload)
{
  std::ostringstream header;
  header << kMagic << " length=" << payload.size() << " crc32=" << crc32_of(payload) << "\n";
  write_atomically_raw(path, header.str() + payload);
}

std::string check_framed(const std::string& text, const std::string& path)
{
  const size_t eol = text.find('\n');
  if (text.empty()) throw CorruptFile(path + ": empty file");
  const std::string header = text.substr(0, eol);
  size_t length = 0;
  unsigned long crc = 0;
  char magic[64] = {0};
  char version[16] = {0};
  if (eol == std::string::npos ||
      std::sscanf(header.c_str(), "%63s %15s length=%zu crc32=%lu", magic, version, &length, &crc) != 4 ||
      std::string(magic) + " " + version != kMagic)
    throw CorruptFile(path + ": not an rgnav checked file (bad header)");
  std::string payload = text.substr(eol + 1);
  if (payload.size() != length)
    throw CorruptFile(path + ": truncated or padded: " + std::to_string(payload.size()) + " bytes, header says " +
                      std::to_string(length));
  if (crc32_of(payload) != crc) throw CorruptFile(path + ": CRC mismatch (corrupted)");
  return payload;
}

std::optional<std::string> read_checked(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  // One read of the whole file (snapshots run to megabytes; a character iterator is slow there).
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0);
  std::string text(static_cast<size_t>(std::max<std::streamoff>(0, size)), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<size_t>(in.gcount()));
  return check_framed(text, path);
}

}  // namespace rgnav::persist
