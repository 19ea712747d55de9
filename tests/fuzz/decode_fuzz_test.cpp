// Robustness of the decode path for every rgnav type: malformed input is refused with a reason
// and counted, never crashes, never allocates what the buffer cannot hold, and whatever is
// accepted round-trips byte for byte (decode_checks.h). Corruptions are aimed with the
// generated wire layout (type_fuzzer.h). Also built and run under ASan+UBSan (ctest
// fuzz_sanitized_*), and the same oracle drives the libFuzzer target. The same corruptions
// through a Node subscription: node_fuzz_test.cpp; every type offered as every other:
// cross_type_fuzz_test.cpp.
#include "type_fuzzer.h"

namespace rgnav::testing {
namespace {

using namespace fuzz;

template <class T>
void fuzz_decode(const char* name)
{
  TypeFuzzer<T> f(name);
  f.run();
  ::testing::Test::RecordProperty("cases", static_cast<int>(f.cases()));
  ::testing::Test::RecordProperty("rejected", static_cast<int>(f.rejected()));
}

// One test per type: DecodeFuzz.laser_scan_t, ...
#define RGNAV_DECODE_TEST(T) \
  TEST(DecodeFuzz, T) { fuzz_decode<T>(#T); }
RGNAV_FOR_EACH_TYPE(RGNAV_DECODE_TEST)
#undef RGNAV_DECODE_TEST

// The harness itself can tell accepted from refused.
TEST(DecodeFuzzHarness, OracleCanFail)
{
  const Bytes valid = encoded(sample<laser_scan_t>(0));
  EXPECT_EQ(check_decode<laser_scan_t>(valid.data(), valid.size()), DecodeOutcome::kAccepted);
  EXPECT_EQ(check_decode<laser_scan_t>(valid.data(), valid.size() - 1), DecodeOutcome::kRejected);
  EXPECT_EQ(check_decode<odometry_t>(valid.data(), valid.size()), DecodeOutcome::kRejected);
}

}  // namespace
}  // namespace rgnav::testing
