// Every layout validation error, triggered by a small hand-written JSON layout; the message must
// name the file and the entry.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tactile/error.h"
#include "tactile/layout/skin_layout.h"
#include "temp_folder.h"
#include "test_paths.h"

namespace tactile {
namespace {

using Json = nlohmann::json;

// Two square taxels (ids 1 and 2, "c01" and "c02"), two modalities, a front/back split.
Json tiny_layout() {
  return Json::parse(R"({
    "id": "tiny", "name": "Tiny", "map_unit": "mm", "sample_rate_hz": 100,
    "modalities": ["force", "prox"],
    "display": {"modality": "prox", "min": 200, "max": 0},
    "channels": [
      {"name": "c01.force", "unit": "N", "modality": "force"},
      {"name": "c01.prox", "unit": "mm", "modality": "prox"},
      {"name": "c02.force", "unit": "N", "modality": "force"},
      {"name": "c02.prox", "unit": "mm", "modality": "prox"}],
    "taxels": [
      {"id": 1, "name": "c01", "x": 0, "y": 0, "w": 10, "h": 10, "area": 100, "shape": "rect",
       "channels": {"force": "c01.force", "prox": "c01.prox"}},
      {"id": 2, "name": "c02", "x": 20, "y": 0, "w": 10, "h": 10, "area": 100, "shape": "rect",
       "channels": {"force": "c02.force", "prox": "c02.prox"}}],
    "groups": [
      {"id": "front", "kind": "side", "name": "front", "taxels": [1]},
      {"id": "back", "kind": "side", "name": "back", "taxels": [2]}],
    "disjoint_kinds": ["side"],
    "classes": ["pat", "poke"]
  })");
}

// The message of the error parsing `text` throws, or "" when it parses.
std::string error_of_text(const std::string& text) {
  try {
    parse_layout_json(text, "tiny.json");
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

std::string error_of(const Json& layout) { return error_of_text(layout.dump()); }

TEST(LayoutJson, TinyLayoutParsesWithChannelsResolvedPerModality) {
  const SkinLayout layout = parse_layout_json(tiny_layout().dump(), "tiny.json");
  EXPECT_EQ(layout.id, "tiny");
  ASSERT_EQ(layout.taxels.size(), 2u);
  EXPECT_EQ(layout.taxels[1].channels, (std::vector<int>{2, 3}));
  EXPECT_EQ(layout.display_modality, "prox");
  EXPECT_DOUBLE_EQ(layout.display_min, 200.0);
  EXPECT_EQ(layout.find_group("back")->taxels, std::vector<int64_t>{2});
}

TEST(LayoutJson, ModalityATaxelLacksGetsMinusOne) {
  Json layout = tiny_layout();
  layout["taxels"][1]["channels"].erase("prox");
  layout["channels"].erase(3);
  const SkinLayout parsed = parse_layout_json(layout.dump(), "tiny.json");
  EXPECT_EQ(parsed.taxels[1].channels, (std::vector<int>{2, -1}));
}

TEST(LayoutValidation, DuplicateTaxelIdNamesTheTaxel) {
  Json layout = tiny_layout();
  layout["taxels"][1]["id"] = 1;
  EXPECT_EQ(error_of(layout), "tiny.json: taxel 1 \"c02\": duplicate id");
}

TEST(LayoutValidation, UnknownChannelNamesTaxelAndChannel) {
  Json layout = tiny_layout();
  layout["taxels"][1]["channels"]["force"] = "c02.f9";
  EXPECT_EQ(error_of(layout), "tiny.json: taxel 2 \"c02\": unknown channel \"c02.f9\"");
}

TEST(LayoutValidation, NaNPositionAsStringOrNullNamesTheTaxel) {
  Json as_string = tiny_layout();
  as_string["taxels"][1]["x"] = "NaN";
  EXPECT_EQ(error_of(as_string), "tiny.json: taxel 2 \"c02\": position is NaN");
  Json as_null = tiny_layout();
  as_null["taxels"][0]["y"] = nullptr;
  EXPECT_EQ(error_of(as_null), "tiny.json: taxel 1 \"c01\": position is NaN");
  Json as_word = tiny_layout();
  as_word["taxels"][0]["y"] = "twelve";
  EXPECT_NE(error_of(as_word).find("taxel 1 \"c01\": y must be a number"), std::string::npos);
}

TEST(LayoutValidation, DisjointGroupsSharingATaxelNameBothGroups) {
  Json layout = tiny_layout();
  layout["groups"][0]["taxels"].push_back(2);
  EXPECT_EQ(error_of(layout),
            "tiny.json: groups \"front\" and \"back\" (kind \"side\", declared disjoint) share "
            "taxel 2");
}

TEST(LayoutValidation, OverlappingGroupsOfAnUndeclaredKindAreAllowed) {
  Json layout = tiny_layout();
  layout["groups"].push_back({{"id", "all"}, {"kind", "region"}, {"taxels", {1, 2}}});
  EXPECT_EQ(error_of(layout), "");
}

TEST(LayoutValidation, GroupWithUnknownTaxelNamesGroupAndTaxel) {
  Json layout = tiny_layout();
  layout["groups"][0]["taxels"].push_back(99);
  EXPECT_EQ(error_of(layout), "tiny.json: group \"front\": unknown taxel 99");
}

TEST(LayoutValidation, DuplicateChannelNameNamesTheChannel) {
  Json layout = tiny_layout();
  layout["channels"][2]["name"] = "c01.force";
  EXPECT_NE(error_of(layout).find("channel \"c01.force\": duplicate channel name"),
            std::string::npos);
}

TEST(LayoutValidation, DuplicateGroupIdNamesTheGroup) {
  Json layout = tiny_layout();
  layout["groups"][1]["id"] = "front";
  EXPECT_EQ(error_of(layout), "tiny.json: group \"front\": duplicate group id");
}

TEST(LayoutValidation, NonPositiveSizeOrAreaNamesTheTaxel) {
  Json zero_width = tiny_layout();
  zero_width["taxels"][0]["w"] = 0;
  EXPECT_NE(error_of(zero_width).find("tiny.json: taxel 1 \"c01\": size must be positive"),
            std::string::npos);
  Json negative_area = tiny_layout();
  negative_area["taxels"][1]["area"] = -4.0;
  EXPECT_NE(error_of(negative_area).find("tiny.json: taxel 2 \"c02\": area must be positive"),
            std::string::npos);
}

TEST(LayoutValidation, MissingRequiredKeysAreNamed) {
  Json no_x = tiny_layout();
  no_x["taxels"][0].erase("x");
  EXPECT_EQ(error_of(no_x), "tiny.json: taxel 1 \"c01\": missing required key \"x\"");
  Json no_id = tiny_layout();
  no_id["taxels"][1].erase("id");
  EXPECT_EQ(error_of(no_id), "tiny.json: taxels[1]: missing required key \"id\"");
  Json no_channels = tiny_layout();
  no_channels.erase("channels");
  EXPECT_EQ(error_of(no_channels), "tiny.json: missing required key \"channels\"");
  Json no_kind = tiny_layout();
  no_kind["groups"][1].erase("kind");
  EXPECT_EQ(error_of(no_kind), "tiny.json: group \"back\": missing required key \"kind\"");
}

TEST(LayoutValidation, SyntaxErrorNamesLineAndColumn) {
  try {
    parse_layout_json("{\n  \"id\": \"tiny\",\n  \"name\": }\n", "tiny.json");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "tiny.json:3 column 11");
    EXPECT_NE(error.message().find("JSON syntax error"), std::string::npos) << error.what();
  }
  EXPECT_NE(error_of_text("").find("JSON syntax error"), std::string::npos);
  EXPECT_NE(error_of_text("{\"id\": \"tiny\"").find("tiny.json:1 column"), std::string::npos);
  // A number no double holds is refused naming the file (it escaped as nlohmann's
  // out_of_range, as the fuzzer found in the JSON frames reader).
  EXPECT_NE(error_of_text("{\"id\": \"tiny\", \"sample_rate_hz\": 2e342}").find("tiny.json"),
            std::string::npos);
}

TEST(LayoutValidation, DuplicateJsonKeyIsNotSilentlyDropped) {
  std::string text = tiny_layout().dump();
  text.insert(1, "\"name\": \"Shadowed\", ");
  EXPECT_EQ(error_of_text(text), "tiny.json: duplicate key \"name\"");
}

TEST(LayoutValidation, UnknownKeyIsRejectedAsATypo) {
  Json top = tiny_layout();
  top["clases"] = Json::array();
  EXPECT_EQ(error_of(top), "tiny.json: unknown key \"clases\"");
  Json in_taxel = tiny_layout();
  in_taxel["taxels"][0]["area_mm"] = 1;
  EXPECT_EQ(error_of(in_taxel), "tiny.json: taxel 1 \"c01\": unknown key \"area_mm\"");
}

TEST(LayoutValidation, ChannelOwnedByTwoTaxelsNamesBoth) {
  Json layout = tiny_layout();
  layout["taxels"][1]["channels"]["force"] = "c01.force";
  EXPECT_EQ(error_of(layout),
            "tiny.json: taxel 2 \"c02\": channel \"c01.force\" already belongs to taxel 1 \"c01\"");
}

TEST(LayoutValidation, ChannelOfTheWrongModalityIsRejected) {
  Json layout = tiny_layout();
  layout["taxels"][0]["channels"]["force"] = "c01.prox";
  layout["taxels"][0]["channels"].erase("prox");
  EXPECT_NE(error_of(layout).find("taxel 1 \"c01\": channel \"c01.prox\" has modality \"prox\""),
            std::string::npos);
}

TEST(LayoutValidation, BadShapeIdOrOutlineIsNamed) {
  Json shape = tiny_layout();
  shape["taxels"][0]["shape"] = "triangle";
  EXPECT_NE(error_of(shape).find("taxel 1 \"c01\": unknown shape \"triangle\""), std::string::npos);
  Json fractional = tiny_layout();
  fractional["taxels"][0]["id"] = 1.5;
  EXPECT_NE(error_of(fractional).find("taxels[0]: id must be a whole number"), std::string::npos);
  Json polygon = tiny_layout();
  polygon["taxels"][0]["shape"] = "polygon";
  EXPECT_NE(error_of(polygon).find("taxel 1 \"c01\": a polygon needs an outline"),
            std::string::npos);
  polygon["taxels"][0]["outline"] = {{0, 0}, {5, 0}, {5, nullptr}};
  EXPECT_EQ(error_of(polygon), "tiny.json: taxel 1 \"c01\": outline point 2 is NaN");
}

TEST(LayoutValidation, DisplayMustNameAModalityAndANonEmptyRange) {
  Json modality = tiny_layout();
  modality["display"]["modality"] = "heat";
  EXPECT_EQ(error_of(modality), "tiny.json: display: unknown modality \"heat\"");
  Json range = tiny_layout();
  range["display"]["max"] = 200;
  EXPECT_NE(error_of(range).find("display: min and max are equal"), std::string::npos);
}

TEST(LayoutValidation, DisjointKindWithoutGroupsIsATypo) {
  Json layout = tiny_layout();
  layout["disjoint_kinds"].push_back("sied");
  EXPECT_EQ(error_of(layout), "tiny.json: disjoint_kinds: no group of kind \"sied\"");
}

TEST(LayoutJson, BodyOutlineIsReadAsPolygonsInMapUnits) {
  Json layout = tiny_layout();
  layout["outline"] = {{{-10, -10}, {30, -10}, {30, 10}, {-10, 10}}, {{0, 20}, {5, 30}, {-5, 30}}};
  const SkinLayout parsed = parse_layout_json(layout.dump(), "tiny.json");
  ASSERT_EQ(parsed.body_outline.size(), 2u);
  EXPECT_EQ(parsed.body_outline[0].size(), 4u);
  EXPECT_DOUBLE_EQ(parsed.body_outline[1][1].x, 5.0);
  EXPECT_DOUBLE_EQ(parsed.body_outline[1][1].y, 30.0);
  // The outline is drawing only: the bounds still hold the taxels alone.
  EXPECT_DOUBLE_EQ(parsed.bounds().first.x, -5.0);
}

TEST(LayoutValidation, BodyOutlineOfTooFewOrNonFinitePointsIsNamed) {
  Json short_polygon = tiny_layout();
  short_polygon["outline"] = {{{0, 0}, {5, 0}}};
  EXPECT_EQ(error_of(short_polygon),
            "tiny.json: outline[0]: a polygon needs at least 3 points (got 2)");
  Json not_a_number = tiny_layout();
  not_a_number["outline"] = {{{0, 0}, {5, 0}, {5, 5}}, {{0, 0}, {5, 0}, {"NaN", 5}}};
  EXPECT_EQ(error_of(not_a_number), "tiny.json: outline[1]: point 2 is NaN");
  Json not_pairs = tiny_layout();
  not_pairs["outline"] = Json::array({5});
  EXPECT_EQ(error_of(not_pairs), "tiny.json: outline[0]: points must be an array, got number");
  Json triple = tiny_layout();
  triple["outline"] = {{{0, 0, 1}, {5, 0}, {5, 5}}};
  EXPECT_EQ(error_of(triple), "tiny.json: outline[0]: points[0] must be a pair [x, y]");
}

TEST(LayoutValidation, ValidateLayoutChecksLayoutsBuiltInCode) {
  SkinLayout layout = make_grid_layout(2, 2);
  layout.taxels[3].position.y = std::nan("");
  try {
    validate_layout(layout, "grid:2x2");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "grid:2x2: taxel 3 \"r1c1\": position is NaN");
  }
}

//---- Files and the asset directory ----------------------------------------------------------

class LayoutFiles : public ::testing::Test {
 protected:
  void SetUp() override { std::filesystem::create_directories(directory_ / "layouts"); }
  void TearDown() override { ::unsetenv("TACTILE_ASSETS"); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(directory_ / "layouts" / name) << text;
  }
  test::TempFolder folder_{"tactile-layout-test"};
  std::filesystem::path directory_ = folder_.path();
};

TEST_F(LayoutFiles, AssetDirectoryComesFromTheEnvironmentWhenSet) {
  write("tiny.json", tiny_layout().dump());
  ::setenv("TACTILE_ASSETS", directory_.c_str(), 1);
  EXPECT_EQ(asset_dir(), directory_.string());
  EXPECT_EQ(load_layout("tiny").taxels.size(), 2u);
  ::unsetenv("TACTILE_ASSETS");
  EXPECT_EQ(asset_dir(), tactile::test::asset_dir());
}

TEST_F(LayoutFiles, FileDeclaringAnotherIdIsRejected) {
  write("other.json", tiny_layout().dump());
  ::setenv("TACTILE_ASSETS", directory_.c_str(), 1);
  try {
    load_layout("other");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(error.where().find("other.json"), std::string::npos);
    EXPECT_EQ(error.message(), "declares id \"tiny\", expected \"other\"");
  }
}

TEST_F(LayoutFiles, ErrorsInAFileNameThatFile) {
  Json broken = tiny_layout();
  broken["taxels"][0]["id"] = 2;
  write("broken.json", broken.dump());
  const std::string path = (directory_ / "layouts" / "broken.json").string();
  try {
    load_layout_file(path);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path);
    EXPECT_EQ(error.message(), "taxel 2 \"c02\": duplicate id");
  }
  try {
    load_layout_file((directory_ / "missing.json").string());
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(error.where().find("missing.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace tactile
