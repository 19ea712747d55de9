// The decode-path robustness checks, shared by the gtest (decode_fuzz_test.cpp) and the
// libFuzzer target (decode_fuzzer.cpp).
//
// The oracle: bus::decode<T> either refuses a buffer (with a reason), or accepts it, and then
// the decoded message re-encodes to exactly the same bytes (LCM's encoding is canonical once the
// validators have refused non-0/1 booleans and embedded NULs). Anything else — a crash, an
// exception, a sanitizer report, a huge allocation, an accepted message that does not
// round-trip — is a bug.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bus/typed.h"

namespace rgnav::testing {

enum class DecodeOutcome { kRejected, kAccepted, kAcceptedButNotCanonical, kRejectedWithoutReason };

template <class T>
DecodeOutcome check_decode(const uint8_t* data, size_t size)
{
  T msg;
  std::string why;
  if (!bus::decode<T>(data, size, &msg, &why))
    return why.empty() ? DecodeOutcome::kRejectedWithoutReason : DecodeOutcome::kRejected;
  std::vector<uint8_t> again;
  std::string why_again;
  if (!bus::encode(msg, &again, &why_again)) return DecodeOutcome::kAcceptedButNotCanonical;
  if (again.size() != size || !std::equal(again.begin(), again.end(), data))
    return DecodeOutcome::kAcceptedButNotCanonical;
  return DecodeOutcome::kAccepted;
}

}  // namespace rgnav::testing
