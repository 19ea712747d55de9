// Every rgnav type offered as every other is refused on the fingerprint (a file of its own: the
// type-by-type instantiations compile in parallel with the other fuzz tests).
#include "type_fuzzer.h"

namespace rgnav::testing {
namespace {

using namespace fuzz;

// A message of one type offered as another is refused on the fingerprint.
template <class T>
void refuse_all_others(const char* name)
{
  const Bytes bytes = encoded(sample<T>(1));
  auto as = [&](auto tag, const char* other) {
    using U = decltype(tag);
    if (std::is_same_v<T, U>) return;
    EXPECT_EQ(check_decode<U>(bytes.data(), bytes.size()), DecodeOutcome::kRejected) << name << " as " << other;
  };
#define RGNAV_AS(U) as(U{}, #U);
  RGNAV_FOR_EACH_TYPE(RGNAV_AS)
#undef RGNAV_AS
}

TEST(CrossTypeFuzz, EveryTypeRefusesEveryOtherType)
{
#define RGNAV_CROSS(T) refuse_all_others<T>(#T);
  RGNAV_FOR_EACH_TYPE(RGNAV_CROSS)
#undef RGNAV_CROSS
}

}  // namespace
}  // namespace rgnav::testing
