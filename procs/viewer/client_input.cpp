#include "viewer/client_input.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

namespace rgnav::viewer {

namespace {

bool fail(std::string* why, const std::string& what)
{
  if (why) *why = what;
  return false;
}

// Constant-time comparison: the token is a secret.
bool same_secret(const std::string& a, const std::string& b)
{
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

}  // namespace

std::optional<GoalRequest> parse_client_input(const std::string& text, std::string* why)
{
  const auto j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return fail(why, "not a JSON object"), std::nullopt;
  const auto type = j.find("type");
  if (type == j.end() || !type->is_string()) return fail(why, "no \"type\""), std::nullopt;
  const std::set<std::string> allowed =
      *type == "goal" ? std::set<std::string>{"type", "region_id", "pose", "token"} : std::set<std::string>{"type", "token"};
  if (*type != "goal" && *type != "cancel") return fail(why, "unknown type"), std::nullopt;
  for (const auto& [key, value] : j.items()) {
    if (!allowed.count(key)) return fail(why, "unknown key \"" + key + "\""), std::nullopt;
  }
  GoalRequest r;
  if (const auto t = j.find("token"); t != j.end()) {
    if (!t->is_string() || t->get_ref<const std::string&>().size() > 256) return fail(why, "bad token"), std::nullopt;
    r.token = t->get<std::string>();
  }
  if (*type == "cancel") {
    r.cancel = true;
    return r;
  }
  const auto id = j.find("region_id");
  if (id == j.end() || !id->is_number_integer() || id->get<int64_t>() <= 0)
    return fail(why, "region_id must be a positive integer"), std::nullopt;
  r.region_id = id->get<int64_t>();
  if (const auto p = j.find("pose"); p != j.end()) {
    if (!p->is_array() || p->size() != 3) return fail(why, "pose must be [x, y, theta]"), std::nullopt;
    double v[3];
    for (int i = 0; i < 3; ++i) {
      if (!(*p)[i].is_number()) return fail(why, "pose must be numbers"), std::nullopt;
      v[i] = (*p)[i].get<double>();
      // No region is 10 km across: a larger coordinate is garbage.
      if (!std::isfinite(v[i]) || std::fabs(v[i]) > 1e4) return fail(why, "pose out of range"), std::nullopt;
    }
    r.region_pose = geometry::Pose2(v[0], v[1], v[2]);
  }
  return r;
}

bool goal_allowed(const GoalRequest& request, bool from_loopback, const std::string& token, std::string* why)
{
  if (from_loopback) return true;
  if (token.empty()) return fail(why, "goals from other hosts are off (no token configured)");
  if (!same_secret(request.token, token)) return fail(why, "wrong token");
  return true;
}

}  // namespace rgnav::viewer
