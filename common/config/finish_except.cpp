#include "config/finish_except.h"

#include <algorithm>

namespace rgnav::config {

void finish_except(const Config& cfg, const std::vector<std::string>& process_sections)
{
  for (const auto& key : cfg.keys()) {
    if (std::find(process_sections.begin(), process_sections.end(), key) != process_sections.end()) continue;
    // A section nobody read (a misspelt section name) has all its keys reported.
    cfg.section(key).finish();
  }
}

}  // namespace rgnav::config
