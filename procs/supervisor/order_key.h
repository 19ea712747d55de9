// The key shared by the deputies and the controllers that sign supervisor orders: where it
// lives, how it is read and checked, and how a new one is made. The key file is one line of
// hex digits (>= 32 bytes of key); it lives outside the source tree and only its owner may
// read it, because whoever holds it can start and stop every process on the robot.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace rgnav::supervisor {

class OrderKeyError : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

// The key file is not there (as opposed to there but refused).
class OrderKeyMissing : public OrderKeyError
{
 public:
  using OrderKeyError::OrderKeyError;
};

struct OrderKey
{
  std::vector<uint8_t> bytes;
  std::string id;  // 16 hex digits of SHA-256(bytes): names the key in orders and messages, reveals nothing
};

// A key from its bytes (>= 32); throws OrderKeyError if shorter.
OrderKey order_key_from_bytes(std::vector<uint8_t> bytes);

// Where the key file is: `configured` (orders.key_file) if not empty; else $RGNAV_ORDERS_KEY
// (test and bench harnesses point it at a key of their own); else /etc/rgnav/orders.key if
// that exists (a robot); else $XDG_CONFIG_HOME/rgnav/orders.key (~/.config/rgnav/orders.key).
std::string order_key_path(const std::string& configured);

// Reads a key file. Throws OrderKeyMissing if there is none, OrderKeyError naming the file if it
// is not a regular file, is readable or writable by others or writable by its group (chmod 600
// it), or holds no key.
OrderKey load_order_key(const std::string& path);

// Writes a new random key (32 bytes from the OS's generator) to `path` with mode 0600, making
// its folder (0700) if needed. An existing file is kept (OrderKeyError) unless `replace`.
OrderKey create_order_key(const std::string& path, bool replace);

}  // namespace rgnav::supervisor
