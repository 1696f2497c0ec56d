// Shards and their part files (tactile/shards/shard.h): which items a shard does, and what
// gather_parts refuses, by name.
#include "tactile/shards/shard.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io_test_files.h"
#include "tactile/error.h"

namespace tactile {
namespace {

using testing::read_text;
using testing::TemporaryDirectory;
using testing::write_text;

// A part of a job of `items` items whose entries hold their index squared.
Part square_part(Shard shard, int64_t items, const std::string& pipeline = "kaboli") {
  Part part;
  part.command = "features";
  part.shard = shard;
  part.inputs = {{"--pipeline", pipeline}};
  part.result = "table.csv";
  part.items = items;
  std::vector<std::string> keys;
  for (int64_t k = 0; k < items; ++k) keys.push_back("r" + std::to_string(k));
  part.plan = plan_digest(keys);
  part.done = nlohmann::json::array();
  for (size_t k : shard.items_of(static_cast<size_t>(items)))
    part.done.push_back({{"index", k}, {"square", k * k}});
  return part;
}

std::string gather_error_of(const std::vector<std::string>& paths) {
  try {
    gather_parts(paths, "features");
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(Shard, ParsesIOfNAndRefusesWhatIsNot) {
  const Shard shard = Shard::parse("2/4");
  EXPECT_EQ(shard.index, 2);
  EXPECT_EQ(shard.count, 4);
  EXPECT_EQ(shard.to_string(), "2/4");
  EXPECT_FALSE(Shard::parse("").active());
  for (const char* bad : {"0/4", "5/4", "2", "2/0", "a/4", "2/4/1", "-1/4", "2/"}) {
    try {
      Shard::parse(bad);
      ADD_FAILURE() << bad << " was taken";
    } catch (const Error& error) {
      EXPECT_EQ(error.where(), "--shard") << bad;
      EXPECT_NE(std::string(error.what()).find(bad), std::string::npos) << error.what();
    }
  }
}

TEST(Shard, EveryItemBelongsToExactlyOneShardRoundRobin) {
  std::vector<int> owners(11, 0);
  for (int index = 1; index <= 3; ++index)
    for (size_t item : Shard{index, 3}.items_of(11)) owners[item] += index;
  EXPECT_EQ(owners, (std::vector<int>{1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2}));
  EXPECT_EQ(Shard{}.items_of(3), (std::vector<size_t>{0, 1, 2}));  // not sharded: all
  EXPECT_TRUE((Shard{4, 4}.items_of(3).empty()));  // more shards than items: an empty share
}

TEST(ShardParts, WrittenPartsGatherInShardOrderAndGiveEveryItemOnce) {
  TemporaryDirectory directory;
  std::vector<std::string> paths;
  for (int index : {3, 1, 2}) {
    paths.push_back(directory.file("p" + std::to_string(index)));
    write_part(paths.back(), square_part({index, 3}, 8));
  }
  const std::vector<Part> parts = gather_parts(paths, "features");
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts[0].shard.index, 1);
  EXPECT_EQ(parts[2].path, paths[0]);
  const std::vector<nlohmann::json> items = items_in_order(parts);
  ASSERT_EQ(items.size(), 8u);
  for (size_t k = 0; k < items.size(); ++k) EXPECT_EQ(items[k].at("square"), k * k);
}

TEST(ShardParts, AMissingShardIsNamedWithItsDefaultPath) {
  TemporaryDirectory directory;
  std::vector<std::string> paths;
  for (int index : {1, 2, 4}) {
    paths.push_back(directory.file("p" + std::to_string(index)));
    write_part(paths.back(), square_part({index, 5}, 9));
  }
  const std::string error = gather_error_of(paths);
  EXPECT_NE(error.find("shards 3/5 (table.csv.part-3-of-5), 5/5"), std::string::npos) << error;
  EXPECT_NE(error.find("are missing"), std::string::npos) << error;
}

TEST(ShardParts, ADuplicatedShardNamesBothFiles) {
  TemporaryDirectory directory;
  const std::string a = directory.file("a"), b = directory.file("b");
  write_part(a, square_part({1, 2}, 4));
  write_part(b, square_part({1, 2}, 4));
  const std::string error = gather_error_of({a, b});
  EXPECT_NE(error.find(b + ": shard 1/2 is given twice: also " + a), std::string::npos) << error;
}

TEST(ShardParts, PartsOfOtherInputsCountsOrWorkAreRefusedNamingTheField) {
  TemporaryDirectory directory;
  const std::string a = directory.file("a"), b = directory.file("b");
  write_part(a, square_part({1, 2}, 4));
  write_part(b, square_part({2, 2}, 4, "generic"));
  std::string error = gather_error_of({a, b});
  EXPECT_NE(error.find("made with --pipeline \"generic\", " + a + " with \"kaboli\""),
            std::string::npos)
      << error;
  write_part(b, square_part({2, 3}, 4));
  EXPECT_NE(gather_error_of({a, b}).find("is one of 3 shards"), std::string::npos);
  write_part(b, square_part({2, 2}, 5));
  EXPECT_NE(gather_error_of({a, b}).find("saw other work"), std::string::npos);
  Part other = square_part({2, 2}, 4);
  other.command = "evaluate";
  write_part(b, other);
  EXPECT_NE(gather_error_of({a, b}).find("a part of `tactile evaluate`, not of `tactile features`"),
            std::string::npos);
}

TEST(ShardParts, ADamagedCutOrForeignFileIsRefusedByName) {
  TemporaryDirectory directory;
  const std::string path = directory.file("part");
  write_part(path, square_part({1, 2}, 6));
  std::string text = read_text(path);
  const size_t at = text.find("\"square\":4");
  ASSERT_NE(at, std::string::npos);
  text[at + 9] = '5';
  write_text(path, text);
  EXPECT_NE(gather_error_of({path}).find(path + ": checksum failed"), std::string::npos);
  write_text(path, text.substr(0, text.size() / 2));
  EXPECT_NE(gather_error_of({path}).find(path + ": not a part file (cut short"), std::string::npos);
  write_text(path, "{\"rows\": 3}");
  EXPECT_NE(gather_error_of({path}).find("not a part file"), std::string::npos);
  EXPECT_NE(gather_error_of({directory.file("absent")}).find("no such part file"),
            std::string::npos);
}

TEST(ShardParts, APartMissingOneOfItsItemsIsRefused) {
  TemporaryDirectory directory;
  const std::string path = directory.file("part");
  Part part = square_part({2, 2}, 6);
  part.done.erase(part.done.begin() + 1);
  write_part(path, part);
  EXPECT_NE(gather_error_of({path}).find("holds 2 of shard 2/2's 3 items"), std::string::npos);
  part = square_part({2, 2}, 6);
  part.done[0]["index"] = 0;  // shard 1's item
  write_part(path, part);
  EXPECT_NE(gather_error_of({path}).find("item 0 is not one of shard 2/2's"), std::string::npos);
}

}  // namespace
}  // namespace tactile
