// Signed supervisor orders: the key file (found, refused when others may read it, made with
// mode 600), and the verification of an order: good, unsigned, wrong key, each field tampered
// with, replayed, stale; the copies of one order carried out once; refusals reported without
// flooding.
#include "order_auth.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gtest/gtest.h>

namespace rgnav::supervisor {
namespace {

using namespace std::chrono_literals;

OrderKey key_of(uint8_t fill) { return order_key_from_bytes(std::vector<uint8_t>(32, fill)); }

class TempDir
{
 public:
  TempDir()
  {
    char tmpl[] = "/tmp/rgnav_order_auth_XXXXXX";
    path_ = mkdtemp(tmpl);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

constexpr int64_t kNow = 1'800'000'000'000'000;  // [us] a wall time

OrderFields signed_order(const OrderKey& key, int64_t order_id = 7, int64_t utime = kNow)
{
  OrderFields o;
  o.utime = utime;
  o.order_id = order_id;
  o.host = "b21r";
  o.order = 3;
  o.target = "lld";
  o.source = "rgnav_ctl@laptop:42";
  sign_order(o, key);
  return o;
}

OrderVerifier verifier(std::optional<OrderKey> key) { return OrderVerifier(std::move(key), "/etc/rgnav/orders.key", 10000ms); }

TEST(OrderAuth, ASignedOrderIsAcceptedAndItsOtherCopiesAreDroppedQuietly)
{
  const OrderKey key = key_of(1);
  OrderVerifier v = verifier(key);
  OrderFields o = signed_order(key);
  EXPECT_EQ(o.key_id, key.id);
  EXPECT_EQ(o.mac.size(), 64u);
  EXPECT_EQ(v.check(o, kNow + 1000).verdict, OrderVerdict::kAccept);
  // The controller's second and third copy: same order id, a nonce (and mac) of their own.
  sign_order(o, key);
  EXPECT_EQ(v.check(o, kNow + 2000).verdict, OrderVerdict::kCopy);
  sign_order(o, key);
  EXPECT_EQ(v.check(o, kNow + 3000).verdict, OrderVerdict::kCopy);
  // A new order of the same sender is carried out.
  EXPECT_EQ(v.check(signed_order(key, 8), kNow + 4000).verdict, OrderVerdict::kAccept);
}

TEST(OrderAuth, UnsignedOrWrongKeyOrNoKeyHereIsRefused)
{
  const OrderKey key = key_of(1);
  OrderVerifier v = verifier(key);
  OrderFields unsigned_order = signed_order(key);
  unsigned_order.mac.clear();
  unsigned_order.key_id.clear();
  auto c = v.check(unsigned_order, kNow);
  EXPECT_EQ(c.verdict, OrderVerdict::kRefuse);
  EXPECT_NE(c.why.find("unsigned"), std::string::npos) << c.why;

  // Signed with another key (its id says so).
  c = v.check(signed_order(key_of(2)), kNow);
  EXPECT_EQ(c.verdict, OrderVerdict::kRefuse);
  EXPECT_NE(c.why.find("another key"), std::string::npos) << c.why;
  // Another key that claims our key's id: the mac does not match.
  OrderFields forged = signed_order(key_of(2));
  forged.key_id = key.id;
  forged.mac = order_mac(forged, key_of(2));
  c = v.check(forged, kNow);
  EXPECT_EQ(c.verdict, OrderVerdict::kRefuse);
  EXPECT_NE(c.why.find("does not match"), std::string::npos) << c.why;

  // A deputy without a key carries out nothing, and says where it looked.
  OrderVerifier keyless = verifier(std::nullopt);
  c = keyless.check(signed_order(key), kNow);
  EXPECT_EQ(c.verdict, OrderVerdict::kRefuse);
  EXPECT_NE(c.why.find("/etc/rgnav/orders.key"), std::string::npos) << c.why;
}

TEST(OrderAuth, EveryFieldIsCoveredByTheMac)
{
  const OrderKey key = key_of(1);
  const std::vector<std::function<void(OrderFields&)>> tamper = {
      [](OrderFields& o) { o.utime += 1; },          [](OrderFields& o) { o.order_id += 1; },
      [](OrderFields& o) { o.host = "b21r-2"; },     [](OrderFields& o) { o.order = 4; },
      [](OrderFields& o) { o.target = "base_driver"; }, [](OrderFields& o) { o.source = "rgnav_ctl@robot:1"; },
      [](OrderFields& o) { o.nonce ^= 1; },          [](OrderFields& o) { o.mac[10] = o.mac[10] == '0' ? '1' : '0'; },
      [](OrderFields& o) { o.mac.pop_back(); },
  };
  for (size_t i = 0; i < tamper.size(); ++i) {
    OrderVerifier v = verifier(key);
    OrderFields o = signed_order(key);
    tamper[i](o);
    const auto c = v.check(o, kNow);
    EXPECT_EQ(c.verdict, OrderVerdict::kRefuse) << "tampered field #" << i;
  }
  // Strings are length-prefixed: moving a character from one field to the next changes the mac.
  OrderFields a = signed_order(key);
  OrderFields b = a;
  a.host = "b21r";
  a.target = "xlld";
  b.host = "b21rx";
  b.target = "lld";
  EXPECT_NE(order_mac_input(a), order_mac_input(b));
}

TEST(OrderAuth, ReplaysAndStaleOrdersAreRefused)
{
  const OrderKey key = key_of(1);
  OrderVerifier v = verifier(key);
  const OrderFields o = signed_order(key);
  EXPECT_EQ(v.check(o, kNow).verdict, OrderVerdict::kAccept);
  // The very same bytes again: a recording played back inside the window.
  auto c = v.check(o, kNow + 500'000);
  EXPECT_EQ(c.verdict, OrderVerdict::kRefuse);
  EXPECT_NE(c.why.find("replay"), std::string::npos) << c.why;
  // Played back after the window (the deputy may have forgotten it by then).
  OrderVerifier fresh = verifier(key);
  c = fresh.check(o, kNow + 10'001'000);
  EXPECT_EQ(c.verdict, OrderVerdict::kRefuse);
  EXPECT_NE(c.why.find("ago"), std::string::npos) << c.why;
  // From the future (a clock far ahead, or a prepared order).
  c = fresh.check(signed_order(key, 9, kNow + 20'000'000), kNow);
  EXPECT_EQ(c.verdict, OrderVerdict::kRefuse);
  EXPECT_NE(c.why.find("future"), std::string::npos) << c.why;
  // Inside the window it is fine.
  EXPECT_EQ(fresh.check(signed_order(key, 10, kNow - 9'000'000), kNow).verdict, OrderVerdict::kAccept);
}

TEST(OrderAuth, TheGateAlertsNamingBothSourcesAndLimitsItsReports)
{
  const OrderKey key = key_of(1);
  OrderGate gate(verifier(key), 10s);
  const auto t0 = OrderGate::Clock::now();
  OrderDecision d = gate.on_order(signed_order(key), kNow, t0);
  EXPECT_TRUE(d.execute);
  EXPECT_TRUE(d.log.empty() && d.alert.empty());

  OrderFields intruder;
  intruder.utime = kNow;
  intruder.order_id = 1;
  intruder.order = 4;
  intruder.source = "evil@somewhere:1";
  d = gate.on_order(intruder, kNow, t0 + 10ms);
  EXPECT_FALSE(d.execute);
  EXPECT_NE(d.log.find("evil@somewhere:1"), std::string::npos) << d.log;
  EXPECT_NE(d.alert.find("evil@somewhere:1"), std::string::npos) << d.alert;
  EXPECT_NE(d.alert.find("rgnav_ctl@laptop:42"), std::string::npos) << d.alert;
  EXPECT_NE(d.alert.find(key.id), std::string::npos) << d.alert;
  // A flood: no log line within the second, no alert within the interval; then one each with the count.
  for (int i = 0; i < 100; ++i) {
    intruder.order_id = 2 + i;
    d = gate.on_order(intruder, kNow, t0 + 20ms);
    EXPECT_TRUE(d.log.empty() && d.alert.empty());
  }
  d = gate.on_order(intruder, kNow, t0 + 1500ms);
  EXPECT_NE(d.log.find("100 more refused"), std::string::npos) << d.log;
  EXPECT_TRUE(d.alert.empty());
  d = gate.on_order(intruder, kNow, t0 + 11s);
  EXPECT_NE(d.alert.find("102 refused since the last alert"), std::string::npos) << d.alert;
  EXPECT_EQ(gate.refused(), 103);
}

TEST(OrderKeyFile, MadeWithMode600ReadBackAndNeverOverwrittenSilently)
{
  TempDir dir;
  const std::string path = dir.file("sub/orders.key");
  const OrderKey made = create_order_key(path, false);
  struct stat st{};
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  ASSERT_EQ(stat(dir.file("sub").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0700u);
  const OrderKey read = load_order_key(path);
  EXPECT_EQ(read.bytes, made.bytes);
  EXPECT_EQ(read.id, made.id);
  EXPECT_EQ(read.id.size(), 16u);
  EXPECT_THROW(create_order_key(path, false), OrderKeyError);
  const OrderKey replaced = create_order_key(path, true);
  EXPECT_NE(replaced.bytes, made.bytes);
  EXPECT_EQ(load_order_key(path).bytes, replaced.bytes);
}

TEST(OrderKeyFile, AKeyOthersCanReadOrNoKeyIsRefusedNamingTheFile)
{
  TempDir dir;
  const std::string path = dir.file("orders.key");
  EXPECT_THROW(load_order_key(path), OrderKeyMissing);
  create_order_key(path, false);
  for (mode_t mode : {0644, 0604, 0620, 0666}) {
    chmod(path.c_str(), mode);
    try {
      load_order_key(path);
      ADD_FAILURE() << "mode " << std::oct << mode << " accepted";
    } catch (const OrderKeyMissing&) {
      ADD_FAILURE() << "reported missing";
    } catch (const OrderKeyError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("chmod 600"), std::string::npos) << e.what();
    }
  }
  chmod(path.c_str(), 0640);  // group may read (a deploy group), not write
  EXPECT_NO_THROW(load_order_key(path));

  const std::vector<std::string> bad_texts = {"", "# only a comment\n", "abc\n", "zz" + std::string(62, '0') + "\n",
                                              std::string(62, 'a') + "\n"};
  for (const std::string& text : bad_texts) {
    const std::string bad = dir.file("bad.key");
    unlink(bad.c_str());
    std::ofstream(bad) << text;
    chmod(bad.c_str(), 0600);
    EXPECT_THROW(load_order_key(bad), OrderKeyError) << "'" << text << "'";
  }
  EXPECT_THROW(load_order_key(dir.file("")), OrderKeyError);  // a folder
}

TEST(OrderKeyFile, PathFromConfigThenEnvironment)
{
  EXPECT_EQ(order_key_path("/srv/k.key"), "/srv/k.key");
  setenv("RGNAV_ORDERS_KEY", "/tmp/x/orders.key", 1);
  EXPECT_EQ(order_key_path(""), "/tmp/x/orders.key");
  EXPECT_EQ(order_key_path("/srv/k.key"), "/srv/k.key");
  unsetenv("RGNAV_ORDERS_KEY");
  const std::string def = order_key_path("");
  EXPECT_TRUE(def == "/etc/rgnav/orders.key" || def.find("/rgnav/orders.key") != std::string::npos) << def;
}

}  // namespace
}  // namespace rgnav::supervisor
