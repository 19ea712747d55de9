// Reference poses for a raw log from a published corrected log of the same run: a raw scan
// whose ranges equal a corrected scan's (within a tolerance, on beams valid in both) takes
// that scan's corrected pose. Agreement with such poses is not ground truth.
#pragma once

#include "importers/log_records.h"

namespace rgnav::importers {

struct ReferenceMatchOptions
{
  double tolerance_m = 0.0101;     // per-beam agreement (the logs print cm)
  double max_valid_range_m = 30.0; // beams beyond are not compared
  double max_mismatch_share = 0.02;  // beams allowed to differ (re-quantisation)
  size_t min_compared_beams = 50;
};

// Adds reference records (at the raw scans' utimes) to `raw` for every corrected scan that
// matches exactly one raw scan. Returns the number added.
size_t add_reference_from_corrected(const ImportedLog& corrected, ImportedLog* raw,
                                    const ReferenceMatchOptions& options = {});

}  // namespace rgnav::importers
