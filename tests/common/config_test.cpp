#include "config/config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "bad_files.h"

namespace rgnav::config {
namespace {

using ::testing::HasSubstr;

std::string error_of(const std::function<void()>& f)
{
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Config, ReadsValuesAndDefaults)
{
  const auto c = Config::parse("a: 1.5\nsec:\n  n: 3\n  s: hi\n  b: true\n  l: [1, 2]\n", "t.yaml");
  EXPECT_DOUBLE_EQ(c.number("a", 0, 0, 10), 1.5);
  EXPECT_DOUBLE_EQ(c.number("missing", 7, 0, 10), 7);
  const auto s = c.section("sec");
  EXPECT_EQ(s.integer("n", 0, 0, 10), 3);
  EXPECT_EQ(s.string("s", ""), "hi");
  EXPECT_TRUE(s.boolean("b", false));
  EXPECT_EQ(s.numbers("l", {}, 0, 5), (std::vector<double>{1, 2}));
  EXPECT_NO_THROW(c.finish());
}

TEST(Config, UnknownKeyNamesFileAndFullPath)
{
  const auto c = Config::parse("sec:\n  good: 1\n  typo_key: 2\n", "config/x.yaml");
  c.section("sec").number("good", 0, 0, 5);
  const std::string e = error_of([&] { c.finish(); });
  EXPECT_THAT(e, HasSubstr("config/x.yaml"));
  EXPECT_THAT(e, HasSubstr("'sec.typo_key'"));
  EXPECT_THAT(e, ::testing::Not(HasSubstr("sec.good")));
}

TEST(Config, UnreadSectionIsUnknown)
{
  const auto c = Config::parse("other:\n  x: 1\n", "f.yaml");
  EXPECT_THAT(error_of([&] { c.finish(); }), HasSubstr("'other'"));
}

TEST(Config, WrongTypeAndRangeNameKey)
{
  const auto c = Config::parse("m:\n  speed: fast\n  limit: 12\n  n: 2.5\n  flag: maybe\n", "r.yaml");
  const auto m = c.section("m");
  EXPECT_THAT(error_of([&] { m.number("speed", 0, 0, 1); }), HasSubstr("r.yaml: key 'm.speed': expected a number"));
  EXPECT_THAT(error_of([&] { m.number("limit", 0, 0, 10); }), HasSubstr("key 'm.limit': value 12 outside [0, 10]"));
  EXPECT_THAT(error_of([&] { m.integer("n", 0, 0, 10); }), HasSubstr("key 'm.n': expected an integer"));
  EXPECT_THAT(error_of([&] { m.boolean("flag", false); }), HasSubstr("key 'm.flag': expected true or false"));
}

TEST(Config, NonFiniteNumbersRefused)
{
  const auto c = Config::parse("x: .nan\ny: .inf\n", "n.yaml");
  EXPECT_THAT(error_of([&] { c.number("x", 0, -1e9, 1e9); }), HasSubstr("'x'"));
  EXPECT_THAT(error_of([&] { c.number("y", 0, -1e9, 1e9); }), HasSubstr("'y'"));
}

TEST(Config, ChoiceListsAllowedValues)
{
  const auto c = Config::parse("mode: turbo\n", "c.yaml");
  EXPECT_THAT(error_of([&] { c.choice("mode", "direct", {"direct", "protocol"}); }),
              HasSubstr("'turbo' is not one of: direct, protocol"));
}

TEST(Config, StringsTakeAListOrOneScalar)
{
  const auto c = Config::parse("many: [a, b]\none: c\nbad: [[x]]\nmap: {k: v}\n", "s.yaml");
  EXPECT_EQ(c.strings("many", {}), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(c.strings("one", {}), (std::vector<std::string>{"c"}));
  EXPECT_EQ(c.strings("missing", {"d"}), (std::vector<std::string>{"d"}));
  EXPECT_THAT(error_of([&] { c.strings("bad", {}); }), HasSubstr("'bad': element 0: expected a string"));
  EXPECT_THAT(error_of([&] { c.strings("map", {}); }), HasSubstr("expected a list of strings"));
}

TEST(Config, ListElementsTrackUnknownKeys)
{
  const auto c = Config::parse("walls:\n  - {x: 1, y: 2}\n  - {x: 3, z: 4}\n", "w.yaml");
  for (const auto& w : c.list("walls")) w.number("x", 0, 0, 9);
  const std::string e = error_of([&] { c.finish(); });
  EXPECT_THAT(e, HasSubstr("walls[0].y"));
  EXPECT_THAT(e, HasSubstr("walls[1].z"));
}

TEST(Config, MissingFileAndBadYaml)
{
  EXPECT_THAT(error_of([] { Config::load("/nonexistent/rgnav.yaml"); }),
              HasSubstr("/nonexistent/rgnav.yaml: cannot open"));
  EXPECT_THAT(error_of([] { Config::parse("a: [1, 2\n", "bad.yaml"); }), HasSubstr("bad.yaml: not valid YAML"));
  EXPECT_THAT(error_of([] { Config::parse("- 1\n- 2\n", "seq.yaml"); }), HasSubstr("top level must be a mapping"));
}

// Issue 35: random bytes, an empty file, white space or comments only (a file cut off inside its
// header comment), and a file cut off inside a key are refused naming the file: none of them is
// read as "all defaults".
TEST(Config, RandomBytesEmptyCommentsOnlyAndCutOffFilesAreRefusedNamingThem)
{
  testing::TempDir dir("config_bad");
  const std::string valid = "# a process config\nnode:\n  name: x\n  heartbeat_hz: 5\nmatcher:\n  max_range_m: 30\n";
  auto files = testing::write_bad_files(dir.path(), "p.yaml", valid, valid.find("heartbeat_hz") + 5);
  files.push_back({"white space", dir.file("space.yaml")});
  testing::write_bytes(files.back().path, "\n  \n\t\n");
  files.push_back({"comments only", dir.file("comments.yaml")});
  testing::write_bytes(files.back().path, valid.substr(0, 10));
  files.push_back({"NUL bytes", dir.file("nul.yaml")});
  testing::write_bytes(files.back().path, std::string("node:\n  name: x\0\0\0", 19));
  for (const auto& f : files) {
    SCOPED_TRACE(f.kind);
    const std::string e = error_of([&] {
      const auto c = Config::load(f.path);
      c.section("node").string("name", "");
      c.section("node").number("heartbeat_hz", 1, 0, 100);
      c.section("matcher").number("max_range_m", 30, 1, 80);
      c.finish();
    });
    EXPECT_THAT(e, ::testing::StartsWith(f.path + ": "));
  }
  testing::write_bytes(dir.file("valid.yaml"), valid);
  EXPECT_EQ(Config::load(dir.file("valid.yaml")).section("node").string("name", ""), "x");
}

TEST(Config, MissingSectionsReadAsDefaults)
{
  const auto c = Config::parse("capture:\n  rate_hz: 5\n", "m.yaml");
  const auto cams = c.section("capture").section("cameras");
  EXPECT_EQ(cams.integer("width", 640, 1, 9000), 640);
  EXPECT_EQ(c.section("channels").string("stereo", "STEREO_IMAGES"), "STEREO_IMAGES");
  EXPECT_DOUBLE_EQ(c.section("capture").number("rate_hz", 1, 0, 10), 5);
  EXPECT_NO_THROW(c.finish());
}

TEST(Config, SectionOfWrongKind)
{
  const auto c = Config::parse("node: 5\n", "k.yaml");
  EXPECT_THAT(error_of([&] { c.section("node"); }), HasSubstr("key 'node': expected a mapping"));
}

TEST(Config, EveryProcessConfigInRepoParses)
{
  // Each config/<process>.yaml must at least be a YAML mapping; the processes themselves
  // validate keys with --check-config (tests of each process).
  const std::string dir = RGNAV_SOURCE_DIR "/config";
  for (const char* name : {"laser_driver", "base_driver", "sim", "scan_mapper", "supervisor"}) {
    const std::string path = dir + "/" + name + ".yaml";
    if (!std::ifstream(path)) continue;
    EXPECT_NO_THROW(Config::load(path)) << path;
  }
}

}  // namespace
}  // namespace rgnav::config
