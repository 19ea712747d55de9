// The emulator's object dictionary is declared in code after the EDS in shared/data; this
// test parses that EDS and checks every object both define agrees: data size, signedness,
// access, PDO mappability and default value ($NODEID resolved).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "emulator/drive_object_dictionary.h"

namespace rgnav::can::emulator {
namespace {

struct EdsEntry
{
  std::map<std::string, std::string> keys;
};

std::map<std::pair<uint16_t, uint8_t>, EdsEntry> parse_eds(std::istream& in)
{
  std::map<std::pair<uint16_t, uint8_t>, EdsEntry> out;
  std::string line;
  EdsEntry* cur = nullptr;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == ';') continue;
    if (line[0] == '[') {
      cur = nullptr;
      const std::string name = line.substr(1, line.find(']') - 1);
      if (name.size() < 4 || !std::isxdigit(static_cast<unsigned char>(name[0]))) continue;
      try {
        const auto index = static_cast<uint16_t>(std::stoul(name.substr(0, 4), nullptr, 16));
        uint8_t sub = 0;
        const auto p = name.find("sub");
        if (p != std::string::npos) sub = static_cast<uint8_t>(std::stoul(name.substr(p + 3), nullptr, 16));
        else if (name.size() != 4) continue;
        cur = &out[{index, sub}];
      } catch (const std::exception&) {
        cur = nullptr;
      }
      continue;
    }
    const auto eq = line.find('=');
    if (cur && eq != std::string::npos) cur->keys[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return out;
}

int64_t parse_value(std::string v, uint8_t node_id)
{
  int64_t base = 0;
  if (v.rfind("$NODEID+", 0) == 0) {
    base = node_id;
    v = v.substr(8);
  }
  return base + std::stoll(v, nullptr, 0);
}

TEST(EdsAgreement, EmulatorObjectDictionaryMatchesTheEds)
{
  const std::string path = std::string(RGNAV_SHARED_DATA_DIR) + "/canopen/cia402_slave.eds";
  std::ifstream in(path);
  if (!in) GTEST_SKIP() << "EDS not found: " << path;
  const auto eds = parse_eds(in);
  ASSERT_GT(eds.size(), 100u);
  const uint8_t node = 7;
  const ObjectDictionary od = make_drive_object_dictionary(node, DriveIdentity{}, DriveDefaults{});
  int compared = 0;
  for (const auto& [key, e] : od.entries()) {
    const auto it = eds.find(key);
    if (it == eds.end()) continue;  // not in the EDS (0x6007, 0x606B, 0x607F: CiA 402 objects it lacks)
    const auto& k = it->second.keys;
    SCOPED_TRACE(::testing::Message() << std::hex << "object 0x" << key.first << ":" << int(key.second));
    ASSERT_TRUE(k.count("DataType"));
    const int type = std::stoi(k.at("DataType"), nullptr, 0);
    const std::map<int, std::pair<int, bool>> types = {{2, {1, true}},  {3, {2, true}},  {4, {4, true}},
                                                       {5, {1, false}}, {6, {2, false}}, {7, {4, false}}};
    ASSERT_TRUE(types.count(type)) << "data type " << type;
    EXPECT_EQ(e.size, types.at(type).first);
    EXPECT_EQ(e.is_signed, types.at(type).second);
    const std::string access = k.at("AccessType");
    if (access == "const") {
      EXPECT_EQ(e.access, Access::kConst);
    } else if (access == "ro") {
      EXPECT_TRUE(e.access == Access::kRo || e.access == Access::kConst);
    } else if (access == "rw" || access == "rww" || access == "rwr") {
      EXPECT_EQ(e.access, Access::kRw);
    }
    if (k.count("PDOMapping")) {
      EXPECT_EQ(e.pdo_mappable, k.at("PDOMapping") == "1");
    }
    if (k.count("DefaultValue") && !k.at("DefaultValue").empty()) {
      const int64_t v = parse_value(k.at("DefaultValue"), node);
      const uint32_t expect = static_cast<uint32_t>(v) & (e.size == 4 ? 0xFFFFFFFFu : (1u << (8 * e.size)) - 1);
      EXPECT_EQ(e.default_value, expect);
    }
    ++compared;
  }
  EXPECT_GT(compared, 90) << "the emulator should model most of the EDS";
  // And the objects profile velocity needs are all there.
  for (uint16_t idx : {0x6040, 0x6041, 0x6060, 0x6061, 0x6064, 0x606C, 0x60FF, 0x1017})
    EXPECT_TRUE(eds.count({idx, 0})) << std::hex << idx;
}

}  // namespace
}  // namespace rgnav::can::emulator
