// The areas of core depend one way (docs/ARCHITECTURE.md, "Areas and their order"): a file may
// include its own area and those below it, never one above. The check reads every header and
// source of core/ as text.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>

#include "test_paths.h"

namespace tactile {
namespace {

// Bottom to top. "base" is core's own top folder (error.h, text.h, parameters.h).
const std::vector<std::string> kAreaOrder = {
    "base",   "jobs",    "stats", "layout", "io",      "shards",      "labelstore",
    "verify", "signal",  "video", "dsp",    "segment", "features",    "ml",
    "labels", "formats", "sim",   "skins",  "live",    "experiments", "cluster"};

// The area a file of core/ belongs to: the folder under include/tactile/ or src/.
std::string area_of(const std::filesystem::path& relative) {
  auto part = relative.begin();
  if (part == relative.end()) return "base";
  if (*part == "include")
    part = std::next(part, 2);  // include/tactile/
  else
    ++part;  // src/
  if (part == relative.end() || std::next(part) == relative.end()) return "base";
  return part->string();
}

TEST(Layering, NoFileOfCoreIncludesAnAreaAboveItsOwn) {
  std::map<std::string, size_t> rank;
  for (size_t k = 0; k < kAreaOrder.size(); ++k) rank[kAreaOrder[k]] = k;
  const std::filesystem::path core =
      std::filesystem::path(test::test_data_dir()).parent_path().parent_path() / "core";
  ASSERT_TRUE(std::filesystem::is_directory(core)) << core;
  const std::regex include_line(R"(^\s*#\s*include\s+"tactile/([a-z_]+)/)");
  size_t files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(core)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".h" && extension != ".cpp") continue;
    ++files;
    const std::string area = area_of(std::filesystem::relative(entry.path(), core));
    ASSERT_TRUE(rank.count(area)) << entry.path() << ": area " << area << " is not in the order";
    std::ifstream in(entry.path());
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      std::smatch match;
      if (!std::regex_search(line, match, include_line)) continue;
      const std::string included = match[1];
      ASSERT_TRUE(rank.count(included))
          << entry.path() << ":" << number << ": area " << included << " is not in the order";
      EXPECT_LE(rank[included], rank[area])
          << entry.path().string() << ":" << number << ": " << area << " includes " << included
          << ", an area above it";
    }
  }
  EXPECT_GT(files, 100u);
}

}  // namespace
}  // namespace tactile
