// Reads a table of string keys (typically a process's channel names) into their fields.
//
//   config::read_strings(c, {{"laser", &ch.laser}, {"odometry", &ch.odometry}});
//
// Each key keeps its field's current value as the default, and keys are read in table order,
// exactly as a hand-written `ch.laser = c.string("laser", ch.laser);` sequence would.
#pragma once

#include <initializer_list>
#include <string>

#include "config/config.h"

namespace rgnav::config {

struct StringField
{
  const char* key;
  std::string* value;
};

inline void read_strings(const Config& c, std::initializer_list<StringField> fields)
{
  for (const StringField& f : fields) *f.value = c.string(f.key, *f.value);
}

}  // namespace rgnav::config
