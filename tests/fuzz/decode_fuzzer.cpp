// libFuzzer target for the decode path of every rgnav type (built with -DRGNAV_FUZZ=ON and
// clang). The first input byte picks the type (index into RGNAV_FOR_EACH_TYPE), the rest is
// the buffer. The oracle is decode_checks.h: refuse with a reason, or accept and round-trip.
// libFuzzer's -malloc_limit_mb catches a decode that allocates what the buffer cannot hold.
#include <cstdio>
#include <cstdlib>

#include "decode_checks.h"

namespace {

using Check = void (*)(const uint8_t*, size_t);

template <class T>
void check(const uint8_t* data, size_t size)
{
  const auto outcome = rgnav::testing::check_decode<T>(data, size);
  if (outcome == rgnav::testing::DecodeOutcome::kAcceptedButNotCanonical ||
      outcome == rgnav::testing::DecodeOutcome::kRejectedWithoutReason) {
    std::fprintf(stderr, "decode oracle violated (outcome %d)\n", static_cast<int>(outcome));
    std::abort();
  }
}

#define RGNAV_ENTRY(T) &check<rgnav::T>,
const Check kChecks[] = {RGNAV_FOR_EACH_TYPE(RGNAV_ENTRY)};
#undef RGNAV_ENTRY

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size < 1) return 0;
  kChecks[data[0] % (sizeof kChecks / sizeof kChecks[0])](data + 1, size - 1);
  return 0;
}
