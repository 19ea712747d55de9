// What may name a region (operators name them with ./rgnav name-region; goals and pose requests
// take regions by name): 1-64 printable ASCII characters (the map pictures draw them with
// fonts that know no more), not blank at either end, and not only digits, so that a tool's
// argument NAME|ID is never ambiguous. Header-only: the message checks (common/msg) use it
// without linking the map model.
#pragma once

#include <algorithm>
#include <cctype>
#include <string>

namespace rgnav::rgmap {

constexpr size_t kMaxRegionNameLength = 64;

inline bool valid_region_name(const std::string& name, std::string* why = nullptr)
{
  const auto no = [why](const char* text) {
    if (why) *why = text;
    return false;
  };
  if (name.empty()) return no("region name is empty");
  if (name.size() > kMaxRegionNameLength) return no("region name longer than 64 characters");
  for (const char c : name)
    if (c < 0x20 || c > 0x7e) return no("region name has a character that is not printable ASCII");
  if (name.front() == ' ' || name.back() == ' ') return no("region name starts or ends with a space");
  if (std::all_of(name.begin(), name.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }))
    return no("region name is only digits (it would read as a region id)");
  return true;
}

// Names compare without regard to case ("Kitchen" is "kitchen").
inline bool same_region_name(const std::string& a, const std::string& b)
{
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace rgnav::rgmap
