// Checked JSON files (persist/checked_json.h): what is written is JSON as it is (any JSON reader
// takes it), reads back equal without its integrity member, and a file damaged in any byte, cut
// off or padded is refused by name; files in the older framing still load.
#include <gtest/gtest.h>

#include "bad_files.h"
#include "persist/atomic_file.h"
#include "persist/checked_json.h"
#include "child_process.h"

namespace rgnav::persist {
namespace {

const nlohmann::json kDoc = {{"schema", "test"}, {"values", {1, 2.5, "three"}}, {"nested", {{"a", true}}}};

TEST(CheckedJson, IsPlainJsonThatReadsBackWithoutItsCheck)
{
  testing::TempDir dir("checked_json");
  const std::string path = dir.file("doc.json");
  write_json_atomically(path, kDoc);
  const std::string text = testing::read_file(path);
  const auto plain = nlohmann::json::parse(text);  // a JSON reader takes it as it is
  EXPECT_TRUE(plain.contains(kIntegrityKey));
  EXPECT_EQ(plain.size(), kDoc.size() + 1);
  EXPECT_EQ(*read_checked_json(path), kDoc);
  EXPECT_FALSE(read_checked_json(dir.file("missing.json")));
}

TEST(CheckedJson, EveryDamagedByteCutOrPaddingIsRefusedNamingTheFile)
{
  testing::TempDir dir("checked_json_bad");
  const std::string path = dir.file("doc.json");
  write_json_atomically(path, kDoc);
  const std::string good = testing::read_file(path);
  for (size_t i = 0; i < good.size(); ++i) {
    std::string bad = good;
    bad[i] = static_cast<char>(bad[i] ^ 0x01);
    SCOPED_TRACE(i);
    EXPECT_THROW(parse_checked_json(bad, path), CorruptFile);
  }
  for (const auto& b : testing::write_bad_files(dir.path(), "doc.json", good)) {
    SCOPED_TRACE(b.kind);
    try {
      read_checked_json(b.path);
      ADD_FAILURE() << "accepted";
    } catch (const CorruptFile& e) {
      EXPECT_NE(std::string(e.what()).find(b.path), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(parse_checked_json(good + " ", path), CorruptFile);
  EXPECT_THROW(parse_checked_json(kDoc.dump(), path), CorruptFile);  // JSON, but unchecked
}

TEST(CheckedJson, OlderFramingStillLoads)
{
  testing::TempDir dir("checked_json_old");
  const std::string path = dir.file("old.json");
  write_atomically(path, kDoc.dump(1));
  EXPECT_EQ(*read_checked_json(path), kDoc);
}

TEST(CheckedJson, RefusesWhatIsNoNonEmptyObject)
{
  testing::TempDir dir("checked_json_obj");
  EXPECT_THROW(write_json_atomically(dir.file("a.json"), nlohmann::json::array({1, 2})), std::invalid_argument);
  EXPECT_THROW(write_json_atomically(dir.file("b.json"), nlohmann::json::object()), std::invalid_argument);
}

}  // namespace
}  // namespace rgnav::persist
