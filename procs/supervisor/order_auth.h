// Signed supervisor orders. Any process on the robot's network can publish on the orders
// channel, so a deputy carries out only orders signed with the shared key (order_key.h):
// HMAC-SHA256 over every field of the order, a time window against old orders played back,
// and a random nonce per copy sent against copies played back inside that window. The
// controller sends each order a few times (UDP may lose one): the copies share the order id
// and differ in nonce, so the deputy acts once and ignores the other copies quietly, while an
// exact copy of one it has already received is a replay, refused and reported.
// No LCM in here: the node converts supervisor_order_t to and from OrderFields.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "config/config.h"
#include "order_key.h"

namespace rgnav::supervisor {

// The fields of supervisor_order_t.
struct OrderFields
{
  int64_t utime = 0;     // [us] wall time of signing
  int64_t order_id = 0;  // shared by the copies of one order
  std::string host;
  int8_t order = 0;
  std::string target;
  std::string source;    // sender, program@host:pid
  int64_t nonce = 0;     // random per copy
  std::string key_id;    // "" unsigned
  std::string mac;       // 64 hex digits, "" unsigned
};

// config/supervisor.yaml, section `orders` (read by the deputy and the controllers).
struct OrderAuthOptions
{
  std::string key_file;  // "": order_key_path("") decides
  // An order signed longer ago than this, or this far in the future, is refused: the hosts'
  // clocks must agree to well within it.
  std::chrono::milliseconds max_age{10000};
};
OrderAuthOptions load_order_auth_options(const config::Config& section);

// The bytes the MAC covers: a version tag, then every field but `mac`, integers big-endian,
// strings length-prefixed (so no two different orders give the same bytes).
std::string order_mac_input(const OrderFields& o);
// HMAC-SHA256 of order_mac_input(o) with the key, 64 lower-case hex digits.
std::string order_mac(const OrderFields& o, const OrderKey& key);
// Sets key_id, a fresh random nonce and the mac (every other field must be final).
void sign_order(OrderFields& o, const OrderKey& key);
// "rgnav_ctl@laptop:4242": who sends, for the order's source field.
std::string order_source(const std::string& program);

enum class OrderVerdict
{
  kAccept,  // carry it out
  kCopy,    // another copy of an order already carried out: nothing to do, nothing to report
  kRefuse,  // not signed with our key, tampered with, stale, or replayed
};

struct OrderCheck
{
  OrderVerdict verdict = OrderVerdict::kRefuse;
  std::string why;  // for kRefuse
};

class OrderVerifier
{
 public:
  // key: nullopt when this deputy has no key: then every order is refused (key_path says
  // where it was looked for).
  OrderVerifier(std::optional<OrderKey> key, std::string key_path, std::chrono::milliseconds max_age);

  // now_utime: this host's wall time [us].
  OrderCheck check(const OrderFields& o, int64_t now_utime);
  bool has_key() const { return key_.has_value(); }
  const std::string& key_id() const;

 private:
  void forget(int64_t now_utime);

  std::optional<OrderKey> key_;
  std::string key_path_;
  int64_t max_age_us_;
  // Valid orders received inside the window: (utime, nonce) of every copy, and (utime,
  // source, order id) of every order carried out. Entries older than the window are dropped:
  // anything that old is refused as stale anyway.
  std::deque<std::pair<int64_t, int64_t>> nonces_;
  struct Done
  {
    int64_t utime;
    std::string source;
    int64_t order_id;
  };
  std::deque<Done> done_;
};

// What the deputy does with an order: carry it out or not, and what to log and alert. A
// refused order is the channel's second source: the alert names it and the owner (the holders
// of the key, and the source of the last order carried out). Refusals are logged at most once
// a second and alerted at most every alert_interval (with the count since), so a flood of
// forged orders cannot flood the log.
struct OrderDecision
{
  bool execute = false;
  std::string log;    // a warning to log ("" none)
  std::string alert;  // an alert to raise ("" none)
};

class OrderGate
{
 public:
  using Clock = std::chrono::steady_clock;
  OrderGate(OrderVerifier verifier, std::chrono::milliseconds alert_interval = std::chrono::seconds(10));

  OrderDecision on_order(const OrderFields& o, int64_t now_utime, Clock::time_point now);
  int64_t refused() const { return refused_; }

 private:
  OrderVerifier verifier_;
  std::chrono::milliseconds alert_interval_;
  std::string last_accepted_source_;
  int64_t refused_ = 0;
  int64_t unlogged_ = 0, unalerted_ = 0;
  std::optional<Clock::time_point> last_log_, last_alert_;
};

// A sender's name as it may appear in a log line: printable ASCII, at most 64 characters.
std::string printable_source(const std::string& s);

}  // namespace rgnav::supervisor
