#include "time/message_time.h"

namespace rgnav::time {

int64_t wall_utime()
{
  using namespace std::chrono;
  return duration_cast<microseconds>(system_clock::now().time_since_epoch()).count();
}

}  // namespace rgnav::time
