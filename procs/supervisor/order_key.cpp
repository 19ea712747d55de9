#include "order_key.h"

#include <fcntl.h>
#include <openssl/evp.h>
#include <openssl/rand.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace rgnav::supervisor {

namespace {

constexpr size_t kMinKeyBytes = 32;
constexpr size_t kNewKeyBytes = 32;
constexpr size_t kMaxFileBytes = 4096;

std::string to_hex(const uint8_t* p, size_t n)
{
  static const char* digits = "0123456789abcdef";
  std::string s;
  s.reserve(2 * n);
  for (size_t i = 0; i < n; ++i) {
    s += digits[p[i] >> 4];
    s += digits[p[i] & 15];
  }
  return s;
}

int hex_value(char c)
{
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string mode_text(mode_t m)
{
  char buf[8];
  std::snprintf(buf, sizeof buf, "%04o", static_cast<unsigned>(m & 07777));
  return buf;
}

// The first line that is not blank or a '#' comment, as bytes.
std::vector<uint8_t> parse_key_text(const std::string& text, const std::string& path)
{
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    size_t b = 0, e = line.size();
    while (b < e && std::isspace(static_cast<unsigned char>(line[b]))) ++b;
    while (e > b && std::isspace(static_cast<unsigned char>(line[e - 1]))) --e;
    if (b == e || line[b] == '#') continue;
    const std::string hex = line.substr(b, e - b);
    if (hex.size() % 2 != 0) throw OrderKeyError(path + ": the key is not whole bytes of hex digits");
    std::vector<uint8_t> bytes;
    for (size_t i = 0; i < hex.size(); i += 2) {
      const int hi = hex_value(hex[i]), lo = hex_value(hex[i + 1]);
      if (hi < 0 || lo < 0) throw OrderKeyError(path + ": the key line holds something other than hex digits");
      bytes.push_back(static_cast<uint8_t>(hi * 16 + lo));
    }
    if (bytes.size() < kMinKeyBytes)
      throw OrderKeyError(path + ": key of " + std::to_string(bytes.size()) + " bytes; at least " +
                          std::to_string(kMinKeyBytes) + " (make one with ./rgnav keygen)");
    return bytes;
  }
  throw OrderKeyError(path + ": no key in the file (make one with ./rgnav keygen)");
}

}  // namespace

OrderKey order_key_from_bytes(std::vector<uint8_t> bytes)
{
  if (bytes.size() < kMinKeyBytes)
    throw OrderKeyError("order key of " + std::to_string(bytes.size()) + " bytes; at least " + std::to_string(kMinKeyBytes));
  uint8_t digest[EVP_MAX_MD_SIZE];
  unsigned len = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &len, EVP_sha256(), nullptr) != 1)
    throw OrderKeyError("SHA-256 failed");
  OrderKey k;
  k.id = to_hex(digest, 8);
  k.bytes = std::move(bytes);
  return k;
}

std::string order_key_path(const std::string& configured)
{
  if (!configured.empty()) {
    const char* home = std::getenv("HOME");
    if (configured.rfind("~/", 0) == 0 && home) return std::string(home) + configured.substr(1);
    return configured;
  }
  if (const char* env = std::getenv("RGNAV_ORDERS_KEY"); env && *env) return env;
  const std::string system = "/etc/rgnav/orders.key";
  std::error_code ec;
  if (std::filesystem::exists(system, ec)) return system;
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg) return std::string(xdg) + "/rgnav/orders.key";
  const char* home = std::getenv("HOME");
  return std::string(home && *home ? home : "/tmp") + "/.config/rgnav/orders.key";
}

OrderKey load_order_key(const std::string& path)
{
  // Checked on the open descriptor, so what is checked is what is read.
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    if (errno == ENOENT)
      throw OrderKeyMissing(path + ": no such key file (make one with ./rgnav keygen; every deputy and controller needs the same)");
    throw OrderKeyError(path + ": cannot open the key file: " + std::strerror(errno));
  }
  struct stat st{};
  std::string text;
  std::string problem;
  if (fstat(fd, &st) != 0) {
    problem = std::string("cannot stat: ") + std::strerror(errno);
  } else if (!S_ISREG(st.st_mode)) {
    problem = "not a regular file";
  } else if (st.st_mode & (S_IRWXO | S_IWGRP)) {
    // Anyone who can read it can sign orders; anyone who can write it can replace it.
    problem = "mode " + mode_text(st.st_mode) + " lets others read or change the key: chmod 600 " + path;
  } else if (st.st_size > static_cast<off_t>(kMaxFileBytes)) {
    problem = "too large for a key file (" + std::to_string(st.st_size) + " bytes)";
  } else {
    text.resize(static_cast<size_t>(st.st_size));
    const ssize_t n = read(fd, text.data(), text.size());
    if (n < 0) problem = std::string("cannot read: ") + std::strerror(errno);
    else text.resize(static_cast<size_t>(n));
  }
  close(fd);
  if (!problem.empty()) throw OrderKeyError(path + ": key file refused: " + problem);
  return order_key_from_bytes(parse_key_text(text, path));
}

OrderKey create_order_key(const std::string& path, bool replace)
{
  std::vector<uint8_t> bytes(kNewKeyBytes);
  if (RAND_bytes(bytes.data(), static_cast<int>(bytes.size())) != 1) throw OrderKeyError("no random bytes from OpenSSL");
  OrderKey key = order_key_from_bytes(bytes);

  const std::filesystem::path p(path);
  if (p.has_parent_path()) {
    std::error_code ec;
    if (!std::filesystem::exists(p.parent_path(), ec)) {
      std::filesystem::create_directories(p.parent_path(), ec);
      if (ec) throw OrderKeyError(path + ": cannot make its folder: " + ec.message());
      std::filesystem::permissions(p.parent_path(), std::filesystem::perms::owner_all, ec);
    }
  }
  const std::string text = "# rgnav supervisor order key (id " + key.id + "); the same file on every deputy and controller\n" +
                           to_hex(bytes.data(), bytes.size()) + "\n";
  // A new file is made exclusively, so nothing else's file is overwritten by a race; a
  // replacement goes through a private temporary and a rename.
  const std::string target = replace ? path + ".new" : path;
  if (replace) unlink(target.c_str());
  const int fd = open(target.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0600);
  if (fd < 0) {
    if (errno == EEXIST) throw OrderKeyError(path + ": a key file is there already (kept; --force replaces it)");
    throw OrderKeyError(path + ": cannot create the key file: " + std::strerror(errno));
  }
  const bool ok = fchmod(fd, 0600) == 0 && write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) &&
                  fsync(fd) == 0;
  const int err = errno;
  close(fd);
  if (!ok || (replace && std::rename(target.c_str(), path.c_str()) != 0)) {
    unlink(target.c_str());
    throw OrderKeyError(path + ": cannot write the key file: " + std::strerror(ok ? errno : err));
  }
  return key;
}

}  // namespace rgnav::supervisor
