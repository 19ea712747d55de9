#include "scan_mapper/scan_ids.h"

namespace rgnav::scan_mapper {

int64_t ScanIdIssuer::id_for(int64_t laser_id, bool* restarted)
{
  const bool back = laser_id <= s_.last_laser_id;
  if (back) s_.offset = s_.last_issued;
  if (restarted) *restarted = back;
  s_.last_laser_id = laser_id;
  return laser_id + s_.offset;
}

}  // namespace rgnav::scan_mapper
