// The five skin layouts, the generic grid/strip layouts, outlines and bounds.
// Validation errors of hand-written JSON are in layout_validation_test.cpp.

#include "tactile/layout/skin_layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "tactile/error.h"

namespace tactile {
namespace {

//---- Geometry helpers ---------------------------------------------------------------------

double distance(const Point2& first, const Point2& second) {
  return std::hypot(first.x - second.x, first.y - second.y);
}

// Separating-axis test for two convex outlines: true when their interiors overlap by more than
// `tolerance` (touching edges do not count).
bool convex_outlines_overlap(const std::vector<Point2>& first, const std::vector<Point2>& second,
                             double tolerance = 1e-3) {
  for (const std::vector<Point2>* polygon : {&first, &second}) {
    const size_t count = polygon->size();
    for (size_t index = 0; index < count; ++index) {
      const Point2& from = (*polygon)[index];
      const Point2& to = (*polygon)[(index + 1) % count];
      const Point2 axis{-(to.y - from.y), to.x - from.x};
      const auto project = [&axis](const std::vector<Point2>& points) {
        double low = INFINITY, high = -INFINITY;
        for (const Point2& point : points) {
          const double value = point.x * axis.x + point.y * axis.y;
          low = std::min(low, value);
          high = std::max(high, value);
        }
        return std::pair{low, high};
      };
      const auto [first_low, first_high] = project(first);
      const auto [second_low, second_high] = project(second);
      const double length = std::hypot(axis.x, axis.y);
      if (std::min(first_high, second_high) - std::max(first_low, second_low) <=
          tolerance * length) {
        return false;  // a separating axis exists
      }
    }
  }
  return true;
}

// Taxel ids per group of one kind (all taxels in one set when kind is empty).
std::map<std::string, std::vector<int64_t>> sheets_of(const SkinLayout& layout,
                                                      const std::string& kind) {
  std::map<std::string, std::vector<int64_t>> sheets;
  if (kind.empty()) {
    for (const Taxel& taxel : layout.taxels) sheets["all"].push_back(taxel.id);
    return sheets;
  }
  for (const Group& group : layout.groups) {
    if (group.kind == kind) sheets[group.id] = group.taxels;
  }
  return sheets;
}

// No two taxels on one sheet/side overlap, and their centres are at least the smaller
// taxel's short side apart (its pitch at the tightest).
void expect_no_overlap_within(const SkinLayout& layout, const std::string& kind) {
  for (const auto& [sheet, ids] : sheets_of(layout, kind)) {
    for (size_t first = 0; first < ids.size(); ++first) {
      const Taxel& one = *layout.find_taxel(ids[first]);
      const std::vector<Point2> one_outline = taxel_outline(one);
      for (size_t second = first + 1; second < ids.size(); ++second) {
        const Taxel& other = *layout.find_taxel(ids[second]);
        EXPECT_FALSE(convex_outlines_overlap(one_outline, taxel_outline(other)))
            << layout.id << " " << sheet << ": taxels " << one.id << " and " << other.id;
        const double pitch =
            std::min(std::min(one.size.x, one.size.y), std::min(other.size.x, other.size.y));
        EXPECT_GE(distance(one.position, other.position), pitch - 1e-3)
            << layout.id << " " << sheet << ": taxels " << one.id << " and " << other.id;
      }
    }
  }
}

// Groups of every declared-disjoint kind share no taxel (checked here independently of
// validate_layout).
void expect_disjoint_kinds_disjoint(const SkinLayout& layout) {
  for (const std::string& kind : layout.disjoint_kinds) {
    std::map<int64_t, std::string> holder;
    for (const Group& group : layout.groups) {
      if (group.kind != kind) continue;
      for (int64_t member : group.taxels) {
        EXPECT_TRUE(holder.emplace(member, group.id).second)
            << layout.id << ": taxel " << member << " in " << holder[member] << " and " << group.id
            << " (kind " << kind << ")";
      }
    }
  }
}

size_t kind_coverage(const SkinLayout& layout, const std::string& kind) {
  std::set<int64_t> covered;
  for (const Group& group : layout.groups) {
    if (group.kind == kind) covered.insert(group.taxels.begin(), group.taxels.end());
  }
  return covered.size();
}

size_t count_kind(const SkinLayout& layout, const std::string& kind) {
  return static_cast<size_t>(
      std::count_if(layout.groups.begin(), layout.groups.end(),
                    [&kind](const Group& group) { return group.kind == kind; }));
}

int channel_of(const SkinLayout& layout, int64_t taxel_id, const std::string& modality) {
  return layout.find_taxel(taxel_id)->channels.at(
      static_cast<size_t>(layout.modality_index(modality)));
}

//---- The five skins -----------------------------------------------------------------------

TEST(BuiltinLayouts, EveryBuiltinLoadsUnderItsOwnIdWithDisjointGroups) {
  for (const std::string& id : known_layout_ids()) {
    const SkinLayout layout = load_layout(id);
    EXPECT_EQ(layout.id, id);
    EXPECT_GT(layout.sample_rate_hz, 0.0) << id;
    EXPECT_FALSE(layout.classes.empty()) << id;
    EXPECT_NO_THROW(validate_layout(layout, id));
    expect_disjoint_kinds_disjoint(layout);
  }
}

TEST(BuiltinLayouts, NaoHas32HexCellsWith8ChannelsEachCellMajor) {
  const SkinLayout nao = load_layout("nao");
  EXPECT_EQ(nao.taxels.size(), 32u);
  EXPECT_EQ(nao.channels.size(), 256u);
  EXPECT_DOUBLE_EQ(nao.sample_rate_hz, 250.0);
  EXPECT_EQ(nao.channel_index("c01.ax"), 0);
  EXPECT_EQ(nao.channel_index("c03.f2"), 2 * 8 + 4);
  EXPECT_EQ(nao.channel_index("c32.temp"), 255);
  EXPECT_EQ(nao.channel_index("c33.ax"), -1);
  EXPECT_EQ(channel_of(nao, 3, "f2"), 20);
  EXPECT_EQ(nao.channels[20].unit, "N");
  EXPECT_EQ(nao.channels[static_cast<size_t>(nao.channel_index("c07.prox"))].unit, "mm");
  EXPECT_EQ(nao.display_modality, "prox");
  EXPECT_DOUBLE_EQ(nao.display_min, 200.0);
  EXPECT_DOUBLE_EQ(nao.display_max, 0.0);
  EXPECT_EQ(nao.classes.size(), 9u);
  const Group* front = nao.find_group("front");
  ASSERT_NE(front, nullptr);
  EXPECT_EQ(front->taxels.front(), 1);
  EXPECT_EQ(front->taxels.back(), 16);
  ASSERT_EQ(nao.groups_of(17, "side").size(), 1u);
  EXPECT_EQ(nao.groups_of(17, "side").front()->id, "back");
  for (const Taxel& cell : nao.taxels) {
    EXPECT_EQ(cell.shape, TaxelShape::kHexagon);
    EXPECT_NEAR(cell.size.y / cell.size.x, 2.0 / std::sqrt(3.0), 1e-3);  // regular hexagon
    EXPECT_NEAR(cell.area, 0.75 * cell.size.x * cell.size.y, 0.1);       // hexagon in its box
  }
  // Front patch (ids 1-16) entirely left of the back patch (17-32).
  double front_right = -INFINITY, back_left = INFINITY;
  for (const Taxel& cell : nao.taxels) {
    if (cell.id <= 16) front_right = std::max(front_right, cell.position.x + cell.size.x / 2);
    if (cell.id > 16) back_left = std::min(back_left, cell.position.x - cell.size.x / 2);
  }
  EXPECT_LT(front_right, back_left);
  expect_no_overlap_within(nao, "side");
}

TEST(BuiltinLayouts, TsaHas21ModulesOfTwo4x4SheetsAt7mmPitch) {
  const SkinLayout tsa = load_layout("tsa");
  EXPECT_EQ(tsa.taxels.size(), 672u);
  EXPECT_EQ(tsa.channels.size(), 672u);
  EXPECT_DOUBLE_EQ(tsa.sample_rate_hz, 8.0);
  EXPECT_EQ(tsa.channel_index("m01.s1.p00"), 0);
  EXPECT_EQ(tsa.channel_index("m01.s2.p00"), 16);
  EXPECT_EQ(tsa.channel_index("m21.s2.p15"), 671);
  EXPECT_EQ(count_kind(tsa, "module"), 21u);
  EXPECT_EQ(count_kind(tsa, "sheet"), 42u);
  EXPECT_EQ(count_kind(tsa, "location"), 9u);
  for (const char* kind : {"module", "sheet", "location"})
    EXPECT_EQ(kind_coverage(tsa, kind), 672u);
  EXPECT_EQ(tsa.find_group("module-07")->taxels.size(), 32u);
  EXPECT_EQ(tsa.find_group("m07.s2")->taxels.size(), 16u);
  // Pads 0 and 1 are row neighbours, 0 and 4 column neighbours: 7 mm apart. (tsa taxel ids
  // are the channel indices.)
  const Taxel& pad0 = *tsa.find_taxel(tsa.channel_index("m05.s1.p00"));
  const Taxel& pad1 = *tsa.find_taxel(tsa.channel_index("m05.s1.p01"));
  const Taxel& pad4 = *tsa.find_taxel(tsa.channel_index("m05.s1.p04"));
  EXPECT_NEAR(pad1.position.x - pad0.position.x, 7.0, 1e-9);
  EXPECT_NEAR(pad4.position.y - pad0.position.y, 7.0, 1e-9);
  EXPECT_NEAR(pad0.area, M_PI * 2.5 * 2.5, 1e-3);  // 5 mm round contact
  EXPECT_EQ(tsa.classes, (std::vector<std::string>{"T1", "T2", "T3", "T4", "T5", "T6"}));
  // The head sits above the thighs on the map.
  const double head_top_y = tsa.find_taxel(tsa.find_group("head-top")->taxels.front())->position.y;
  const double thigh_y = tsa.find_taxel(tsa.find_group("thigh-left")->taxels.front())->position.y;
  EXPECT_LT(head_top_y, thigh_y);
  expect_no_overlap_within(tsa, "sheet");
  expect_no_overlap_within(tsa, "location");
  // The robot's outline (head, torso, two arms, two thighs) surrounds every pad.
  ASSERT_EQ(tsa.body_outline.size(), 6u);
  for (const Taxel& pad : tsa.taxels) {
    const auto inside = [&pad](const std::vector<Point2>& polygon) {
      bool odd = false;  // even-odd rule along a ray to the right
      for (size_t a = 0, b = polygon.size() - 1; a < polygon.size(); b = a++) {
        const Point2& p = polygon[a];
        const Point2& q = polygon[b];
        if ((p.y > pad.position.y) != (q.y > pad.position.y) &&
            pad.position.x < p.x + (q.x - p.x) * (pad.position.y - p.y) / (q.y - p.y))
          odd = !odd;
      }
      return odd;
    };
    EXPECT_TRUE(std::any_of(tsa.body_outline.begin(), tsa.body_outline.end(), inside)) << pad.name;
  }
}

TEST(BuiltinLayouts, FurHas160CellsGrowingFrom2cmOnTopTo4cmBelow) {
  const SkinLayout fur = load_layout("fur");
  EXPECT_EQ(fur.taxels.size(), 160u);
  EXPECT_EQ(fur.channels.size(), 160u);
  EXPECT_DOUBLE_EQ(fur.sample_rate_hz, 15.0);
  EXPECT_EQ(fur.channel_index("f000"), 0);
  EXPECT_EQ(fur.channel_index("f159"), 159);
  EXPECT_NEAR(fur.find_taxel(0)->size.x, 20.0, 1e-9);
  EXPECT_NEAR(fur.find_taxel(0)->area, 400.0, 1e-6);
  EXPECT_NEAR(fur.find_taxel(159)->size.x, 40.0, 1e-9);
  EXPECT_NEAR(fur.find_taxel(159)->area, 1600.0, 1e-6);
  for (int64_t id = 16; id < 160; ++id) {  // never shrinks from one row to the next
    EXPECT_GE(fur.find_taxel(id)->area, fur.find_taxel(id - 16)->area);
    EXPECT_GT(fur.find_taxel(id)->position.y, fur.find_taxel(id - 16)->position.y);
  }
  EXPECT_EQ(count_kind(fur, "region"), 3u);
  EXPECT_EQ(kind_coverage(fur, "region"), 160u);
  EXPECT_DOUBLE_EQ(fur.display_min, 1023.0);  // raw falls under pressure
  EXPECT_EQ(fur.classes.size(), 6u);
  expect_no_overlap_within(fur, "");
}

TEST(BuiltinLayouts, RobovieHas274FilmsByBodyPartFrontLeftBackRight) {
  const SkinLayout robovie = load_layout("robovie");
  EXPECT_EQ(robovie.taxels.size(), 274u);
  EXPECT_EQ(robovie.channels.size(), 274u);
  EXPECT_DOUBLE_EQ(robovie.sample_rate_hz, 100.0);
  EXPECT_EQ(robovie.channel_index("s001"), 0);
  EXPECT_EQ(robovie.channel_index("s274"), 273);
  EXPECT_EQ(channel_of(robovie, 274, "piezo"), 273);
  EXPECT_EQ(kind_coverage(robovie, "body-part"), 274u);
  EXPECT_EQ(kind_coverage(robovie, "side"), 274u);
  EXPECT_GE(count_kind(robovie, "body-part"), 10u);
  for (const Taxel& film : robovie.taxels) {
    EXPECT_TRUE(film.size.x == 30.0 || film.size.x == 50.0) << film.id;
    EXPECT_DOUBLE_EQ(film.area, film.size.x * film.size.y);
    EXPECT_EQ(robovie.groups_of(film.id, "body-part").front()->id, film.body_part);
  }
  double front_right = -INFINITY, back_left = INFINITY;
  for (int64_t id : robovie.find_group("front")->taxels) {
    front_right = std::max(front_right, robovie.find_taxel(id)->position.x);
  }
  for (int64_t id : robovie.find_group("back")->taxels) {
    back_left = std::min(back_left, robovie.find_taxel(id)->position.x);
  }
  EXPECT_LT(front_right, back_left);
  ASSERT_EQ(robovie.classes.size(), 15u);
  EXPECT_EQ(robovie.classes.front(), "Hello.");
  EXPECT_EQ(robovie.classes[7], "I wish you'd pat me on the head");
  EXPECT_EQ(robovie.classes.back(), "Bye-bye!");
  expect_no_overlap_within(robovie, "side");
}

TEST(BuiltinLayouts, FluxHasTwoOrthogonalLayersAndTwoVirtualSums) {
  const SkinLayout flux = load_layout("flux");
  EXPECT_EQ(flux.taxels.size(), 8u);
  ASSERT_EQ(flux.channels.size(), 10u);
  EXPECT_DOUBLE_EQ(flux.sample_rate_hz, 1000.0);
  const std::vector<std::string> order{"x1", "x2", "x3", "x4", "x_sum",
                                       "y1", "y2", "y3", "y4", "y_sum"};
  for (size_t index = 0; index < order.size(); ++index) {
    EXPECT_EQ(flux.channels[index].name, order[index]);
  }
  std::set<int> owned;
  for (const Taxel& stripe : flux.taxels) owned.insert(stripe.channels.front());
  EXPECT_EQ(owned.count(flux.channel_index("x_sum")), 0u);
  EXPECT_EQ(owned.count(flux.channel_index("y_sum")), 0u);
  EXPECT_EQ(owned.size(), 8u);
  double top_bottom_edge = -INFINITY, bottom_top_edge = INFINITY;
  for (int64_t id : flux.find_group("top")->taxels) {
    const Taxel& stripe = *flux.find_taxel(id);
    EXPECT_GT(stripe.size.y, stripe.size.x);  // runs along y
    top_bottom_edge = std::max(top_bottom_edge, stripe.position.y + stripe.size.y / 2);
  }
  for (int64_t id : flux.find_group("bottom")->taxels) {
    const Taxel& stripe = *flux.find_taxel(id);
    EXPECT_GT(stripe.size.x, stripe.size.y);  // orthogonal: runs along x
    bottom_top_edge = std::min(bottom_top_edge, stripe.position.y - stripe.size.y / 2);
  }
  EXPECT_LT(top_bottom_edge, bottom_top_edge);  // top layer drawn above
  double previous_x = -INFINITY;
  for (int zone = 1; zone <= 4; ++zone) {
    const Group* group = flux.find_group("zone" + std::to_string(zone));
    ASSERT_NE(group, nullptr);
    ASSERT_EQ(group->taxels.size(), 1u);
    const Taxel& stripe = *flux.find_taxel(group->taxels.front());
    EXPECT_EQ(stripe.name, "x" + std::to_string(zone));
    EXPECT_GT(stripe.position.x, previous_x);  // zones 1..4 along x
    previous_x = stripe.position.x;
  }
  EXPECT_EQ(flux.classes.size(), 6u);
  expect_no_overlap_within(flux, "layer");
}

//---- Generic layouts ----------------------------------------------------------------------

TEST(GenericLayouts, GridIsRowMajorAt10mmPitchWithOneGroupPerRow) {
  const SkinLayout grid = load_layout("grid:3x4");
  EXPECT_EQ(grid.id, "grid:3x4");
  ASSERT_EQ(grid.taxels.size(), 12u);
  EXPECT_EQ(grid.channel_index("ch11"), 11);
  EXPECT_EQ(grid.modalities, std::vector<std::string>{"value"});
  const Taxel& middle = *grid.find_taxel(5);  // row 1, column 1
  EXPECT_DOUBLE_EQ(middle.position.x, 15.0);
  EXPECT_DOUBLE_EQ(middle.position.y, 15.0);
  EXPECT_EQ(middle.channels, std::vector<int>{5});
  ASSERT_EQ(count_kind(grid, "row"), 3u);
  EXPECT_EQ(grid.find_group("row1")->taxels, (std::vector<int64_t>{4, 5, 6, 7}));
  const auto [low, high] = grid.bounds();
  EXPECT_DOUBLE_EQ(low.x, 0.0);
  EXPECT_DOUBLE_EQ(low.y, 0.0);
  EXPECT_DOUBLE_EQ(high.x, 40.0);
  EXPECT_DOUBLE_EQ(high.y, 30.0);
  EXPECT_NO_THROW(validate_layout(grid, grid.id));
}

TEST(GenericLayouts, StripIsOneRowOfChannels) {
  const SkinLayout strip = load_layout("strip:8");
  ASSERT_EQ(strip.taxels.size(), 8u);
  for (size_t index = 0; index < 8; ++index) {
    EXPECT_EQ(strip.channels[index].name, "ch" + std::to_string(index));
    EXPECT_DOUBLE_EQ(strip.taxels[index].position.x, 5.0 + 10.0 * static_cast<double>(index));
    EXPECT_DOUBLE_EQ(strip.taxels[index].position.y, 5.0);
  }
  EXPECT_NO_THROW(validate_layout(strip, strip.id));
}

TEST(GenericLayouts, StripInRowsKeepsNamesAndChannelsAndWrapsByColumns) {
  const SkinLayout strip = load_layout("strip:10");
  const SkinLayout rows = strip_in_rows(strip, 4);
  ASSERT_EQ(rows.taxels.size(), 10u);
  const Taxel& sixth = rows.taxels[5];  // row 1, column 1
  EXPECT_EQ(sixth.name, strip.taxels[5].name);
  EXPECT_EQ(sixth.channels, strip.taxels[5].channels);
  EXPECT_DOUBLE_EQ(sixth.position.x, 15.0);
  EXPECT_DOUBLE_EQ(sixth.position.y, 15.0);
  EXPECT_DOUBLE_EQ(rows.taxels[9].position.y, 25.0);  // the third row holds two
  EXPECT_NO_THROW(validate_layout(rows, rows.id));
  EXPECT_THROW(strip_in_rows(load_layout("grid:2x2"), 2), Error);
  EXPECT_THROW(strip_in_rows(strip, 0), Error);
}

TEST(GenericLayouts, StripColumnsToFitGiveTheLargestSquareCells) {
  EXPECT_EQ(strip_columns_to_fit(64, 640.0, 10.0), 64);   // a wide panel: one row
  EXPECT_EQ(strip_columns_to_fit(64, 400.0, 400.0), 8);   // a square panel: 8 x 8
  EXPECT_EQ(strip_columns_to_fit(64, 400.0, 200.0), 12);  // 6 rows of 33 px (not 8 x 8 of 25)
  EXPECT_EQ(strip_columns_to_fit(1, 50.0, 500.0), 1);
}

TEST(GenericLayouts, LargestAllowedGridHas65536Taxels) {
  EXPECT_EQ(load_layout("grid:256x256").taxels.size(), 65536u);
}

TEST(GenericLayouts, BadIdsThrowNamingTheId) {
  for (const std::string id :
       {"grid:0x3", "grid:4", "grid:axb", "grid:4x", "grid:-1x3", "grid:4x4x4", "grid:300x300",
        "grid:99999999999999999999x1", "strip:0", "strip:", "strip:70000", "strip:1.5", "foo",
        "../nao", ""}) {
    try {
      load_layout(id);
      ADD_FAILURE() << "no error for " << id;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("layout " + id), std::string::npos) << error.what();
    }
  }
}

//---- Outlines and bounds ------------------------------------------------------------------

TEST(NearestTaxel, DistancesAreToTheClosestOtherCentre) {
  SkinLayout layout = load_layout("grid:3x4");
  layout.taxels[11].position = {100.0, 100.0};  // one taxel far from the rest
  const std::vector<double> nearest = nearest_taxel_distances(layout);
  ASSERT_EQ(nearest.size(), 12u);
  EXPECT_DOUBLE_EQ(nearest[0], 10.0);
  EXPECT_DOUBLE_EQ(nearest[5], 10.0);
  // Taxel 11 is nearest to taxel 10 at (25, 25).
  EXPECT_DOUBLE_EQ(nearest[11], std::hypot(75.0, 75.0));
  const std::vector<double> alone = nearest_taxel_distances(load_layout("strip:1"));
  EXPECT_TRUE(std::isinf(alone.at(0)));
  const SkinLayout tsa = load_layout("tsa");
  const std::vector<double> pads = nearest_taxel_distances(tsa);
  EXPECT_NEAR(*std::max_element(pads.begin(), pads.end()), 7.0, 1e-9);  // the pad pitch
}

TEST(TaxelOutline, PointyHexagonHasSixVerticesAtItsCornerRadius) {
  Taxel cell;
  cell.position = {5.0, 7.0};
  cell.size = {std::sqrt(3.0) * 10.0, 20.0};
  cell.shape = TaxelShape::kHexagon;
  const std::vector<Point2> outline = taxel_outline(cell);
  ASSERT_EQ(outline.size(), 6u);
  for (const Point2& vertex : outline) EXPECT_NEAR(distance(vertex, cell.position), 10.0, 1e-9);
  EXPECT_NEAR(outline.front().x, 5.0, 1e-9);  // a corner straight above the centre
  EXPECT_NEAR(outline.front().y, -3.0, 1e-9);
}

TEST(TaxelOutline, FlatHexagonHasSixVerticesAtItsCornerRadius) {
  Taxel cell;
  cell.size = {20.0, std::sqrt(3.0) * 10.0};
  cell.shape = TaxelShape::kHexagon;
  const std::vector<Point2> outline = taxel_outline(cell);
  ASSERT_EQ(outline.size(), 6u);
  for (const Point2& vertex : outline) EXPECT_NEAR(distance(vertex, Point2{}), 10.0, 1e-9);
  EXPECT_NEAR(outline.front().x, -10.0, 1e-9);  // a corner straight left of the centre
}

TEST(TaxelOutline, RectangleCircleAndExplicitOutlines) {
  Taxel pad;
  pad.position = {1.0, 2.0};
  pad.size = {4.0, 6.0};
  const std::vector<Point2> box = taxel_outline(pad);
  ASSERT_EQ(box.size(), 4u);
  EXPECT_DOUBLE_EQ(box[0].x, -1.0);
  EXPECT_DOUBLE_EQ(box[0].y, -1.0);
  EXPECT_DOUBLE_EQ(box[2].x, 3.0);
  EXPECT_DOUBLE_EQ(box[2].y, 5.0);
  pad.shape = TaxelShape::kCircle;
  pad.size = {5.0, 5.0};
  const std::vector<Point2> round = taxel_outline(pad);
  EXPECT_GE(round.size(), 16u);
  for (const Point2& vertex : round) EXPECT_NEAR(distance(vertex, pad.position), 2.5, 1e-9);
  pad.shape = TaxelShape::kPolygon;
  pad.outline = {{0, 0}, {3, 0}, {0, 3}};
  EXPECT_EQ(taxel_outline(pad).size(), 3u);
  EXPECT_DOUBLE_EQ(taxel_outline(pad)[1].x, 3.0);
}

TEST(LayoutBounds, NaoBoundsSpanBothHoneycombsAndTheGap) {
  const SkinLayout nao = load_layout("nao");
  const auto [low, high] = nao.bounds();
  const double width = std::sqrt(3.0) * 14.0;  // flat-to-flat of a 14 mm-side cell
  EXPECT_NEAR(low.x, 0.0, 1e-2);
  EXPECT_NEAR(low.y, 0.0, 1e-2);
  EXPECT_NEAR(high.x, 2 * 4.5 * width + 40.0, 1e-2);  // two patches of 4.5 cells + 40 mm gap
  EXPECT_NEAR(high.y, 3 * 21.0 + 28.0, 1e-2);         // 3 row pitches + one cell height
}

TEST(LayoutBounds, EmptyLayoutHasAnEmptyBoxAtTheOrigin) {
  const auto [low, high] = SkinLayout{}.bounds();
  EXPECT_EQ(low.x, 0.0);
  EXPECT_EQ(high.y, 0.0);
}

}  // namespace
}  // namespace tactile
