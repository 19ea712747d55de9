#include "order_auth.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#include "config/duration_fields.h"

namespace rgnav::supervisor {

namespace {

// Changing what the MAC covers changes this tag, so old and new signers never agree by accident.
constexpr char kMacTag[] = "rgnav supervisor_order_t v1";

void put_u64(std::string& out, uint64_t v)
{
  for (int i = 7; i >= 0; --i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

void put_string(std::string& out, const std::string& s)
{
  put_u64(out, s.size());
  out += s;
}

const char* order_name(int8_t o)
{
  static const char* names[] = {"?", "start", "stop", "restart", "shutdown"};
  return names[o >= 1 && o <= 4 ? o : 0];
}

std::string describe(const OrderFields& o)
{
  std::string s = std::string("order ") + order_name(o.order);
  if (!o.target.empty()) s += " '" + printable_source(o.target) + "'";
  return s + " from '" + (o.source.empty() ? std::string("(no source)") : printable_source(o.source)) + "'";
}

}  // namespace

OrderAuthOptions load_order_auth_options(const config::Config& section)
{
  OrderAuthOptions o;
  o.key_file = section.string("key_file", o.key_file);
  o.max_age = config::milliseconds(section, "max_age_ms", o.max_age, 500, 600000);
  return o;
}

std::string order_mac_input(const OrderFields& o)
{
  std::string b(kMacTag, sizeof kMacTag);  // with its NUL: the tag ends unambiguously
  put_u64(b, static_cast<uint64_t>(o.utime));
  put_u64(b, static_cast<uint64_t>(o.order_id));
  put_string(b, o.host);
  b += static_cast<char>(o.order);
  put_string(b, o.target);
  put_string(b, o.source);
  put_u64(b, static_cast<uint64_t>(o.nonce));
  put_string(b, o.key_id);
  return b;
}

std::string order_mac(const OrderFields& o, const OrderKey& key)
{
  const std::string input = order_mac_input(o);
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned len = 0;
  if (!HMAC(EVP_sha256(), key.bytes.data(), static_cast<int>(key.bytes.size()),
            reinterpret_cast<const unsigned char*>(input.data()), input.size(), md, &len))
    throw OrderKeyError("HMAC-SHA256 failed");
  static const char* digits = "0123456789abcdef";
  std::string hex;
  for (unsigned i = 0; i < len; ++i) {
    hex += digits[md[i] >> 4];
    hex += digits[md[i] & 15];
  }
  return hex;
}

void sign_order(OrderFields& o, const OrderKey& key)
{
  uint64_t nonce = 0;
  if (RAND_bytes(reinterpret_cast<unsigned char*>(&nonce), sizeof nonce) != 1) throw OrderKeyError("no random bytes from OpenSSL");
  o.nonce = static_cast<int64_t>(nonce);
  o.key_id = key.id;
  o.mac = order_mac(o, key);
}

std::string order_source(const std::string& program)
{
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  return program + "@" + host + ":" + std::to_string(getpid());
}

std::string printable_source(const std::string& s)
{
  std::string out;
  for (char c : s) {
    if (out.size() >= 64) {
      out += "...";
      break;
    }
    out += (c >= 0x20 && c < 0x7f) ? c : '?';
  }
  return out;
}

OrderVerifier::OrderVerifier(std::optional<OrderKey> key, std::string key_path, std::chrono::milliseconds max_age)
    : key_(std::move(key)), key_path_(std::move(key_path)), max_age_us_(max_age.count() * 1000)
{
}

const std::string& OrderVerifier::key_id() const
{
  static const std::string none;
  return key_ ? key_->id : none;
}

void OrderVerifier::forget(int64_t now_utime)
{
  const int64_t oldest = now_utime - max_age_us_;
  nonces_.erase(std::remove_if(nonces_.begin(), nonces_.end(), [&](const auto& n) { return n.first < oldest; }), nonces_.end());
  done_.erase(std::remove_if(done_.begin(), done_.end(), [&](const Done& d) { return d.utime < oldest; }), done_.end());
  // Only orders with a valid mac get here, so only key holders can fill the memory; bounded anyway.
  while (nonces_.size() > 4096) nonces_.pop_front();
  while (done_.size() > 4096) done_.pop_front();
}

OrderCheck OrderVerifier::check(const OrderFields& o, int64_t now_utime)
{
  const auto refuse = [](std::string why) { return OrderCheck{OrderVerdict::kRefuse, std::move(why)}; };
  if (!key_) return refuse("this deputy has no order key (looked for " + key_path_ + "; ./rgnav keygen makes one)");
  if (o.mac.empty() || o.key_id.empty()) return refuse("unsigned");
  if (o.key_id != key_->id)
    return refuse("signed with another key (id " + printable_source(o.key_id) + ", this deputy's is " + key_->id + ")");
  const std::string expected = order_mac(o, *key_);
  if (o.mac.size() != expected.size() || CRYPTO_memcmp(o.mac.data(), expected.data(), expected.size()) != 0)
    return refuse("signature does not match (tampered with, or a wrong key)");
  // Signed by a key holder. Old or future orders may be recordings played back.
  const int64_t age = now_utime - o.utime;
  if (age > max_age_us_ || age < -max_age_us_)
    return refuse("signed " + std::to_string(age / 1000) + " ms " + (age > 0 ? "ago" : "in the future") +
                  ", outside the window of " + std::to_string(max_age_us_ / 1000) + " ms (a replay, or clocks apart)");
  forget(now_utime);
  const auto seen = std::find_if(nonces_.begin(), nonces_.end(), [&](const auto& n) { return n.second == o.nonce; });
  if (seen != nonces_.end()) return refuse("replay: this very copy (nonce) was received before");
  nonces_.emplace_back(o.utime, o.nonce);
  const bool done = std::any_of(done_.begin(), done_.end(),
                                [&](const Done& d) { return d.order_id == o.order_id && d.source == o.source; });
  if (done) return {OrderVerdict::kCopy, ""};
  done_.push_back({o.utime, o.source, o.order_id});
  return {OrderVerdict::kAccept, ""};
}

OrderGate::OrderGate(OrderVerifier verifier, std::chrono::milliseconds alert_interval)
    : verifier_(std::move(verifier)), alert_interval_(alert_interval)
{
}

OrderDecision OrderGate::on_order(const OrderFields& o, int64_t now_utime, Clock::time_point now)
{
  OrderDecision d;
  const OrderCheck c = verifier_.check(o, now_utime);
  if (c.verdict != OrderVerdict::kRefuse) {
    d.execute = c.verdict == OrderVerdict::kAccept;
    if (d.execute) last_accepted_source_ = o.source;
    return d;
  }
  ++refused_;
  ++unlogged_;
  ++unalerted_;
  const std::string what = describe(o) + " refused: " + c.why;
  if (!last_log_ || now - *last_log_ >= std::chrono::seconds(1)) {
    d.log = what;
    if (unlogged_ > 1) d.log += " (" + std::to_string(unlogged_ - 1) + " more refused since the last report)";
    last_log_ = now;
    unlogged_ = 0;
  }
  if (!last_alert_ || now - *last_alert_ >= alert_interval_) {
    // Both sources: the refused one, and who owns the channel.
    d.alert = "SUPERVISOR_ORDERS: " + what + "; orders are taken only from holders of key " +
              (verifier_.has_key() ? verifier_.key_id() : std::string("(none here)")) + ", last from '" +
              (last_accepted_source_.empty() ? std::string("nobody yet") : printable_source(last_accepted_source_)) + "'";
    if (unalerted_ > 1) d.alert += " (" + std::to_string(unalerted_) + " refused since the last alert)";
    last_alert_ = now;
    unalerted_ = 0;
  }
  return d;
}

}  // namespace rgnav::supervisor
