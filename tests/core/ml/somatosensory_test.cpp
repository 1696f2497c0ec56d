// The somatosensory map (spec §4.8): taxels touched together land together; pooled
// correlations equal one pass over all samples; the cache beside a recording is used
// while the recording is unchanged.
#include "tactile/ml/somatosensory.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"

namespace tactile {
namespace {

// Six strip taxels: 0-2 follow one random drive, 3-5 another, all a little of a common
// one (the robot's own motion), plus noise. (Fully independent groups would give -ln|R|
// of pure noise across them: distances scattered from 3 to 8 that no plane can hold.)
Stream two_groups(int64_t samples, uint64_t seed) {
  const SkinLayout layout = load_layout("strip:6");
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 100.0;
  for (const Channel& channel : layout.channels) stream.channels.push_back(channel.name);
  stream.units.assign(layout.channels.size(), "");
  stream.samples = SampleMatrix::Zero(samples, 6);
  std::mt19937_64 random(seed);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  for (int64_t row = 0; row < samples; ++row) {
    const float a = normal(random), b = normal(random), common = normal(random);
    for (int taxel = 0; taxel < 6; ++taxel)
      stream.samples(row, taxel) = (taxel < 3 ? a : b) + 0.4f * common + 0.3f * normal(random);
  }
  return stream;
}

double distance(const SomatosensoryMap& map, size_t i, size_t j) {
  return std::hypot(map.positions[i].x - map.positions[j].x,
                    map.positions[i].y - map.positions[j].y);
}

TEST(SomatosensoryMap, TaxelsTouchedTogetherLieTogether) {
  const SkinLayout layout = load_layout("strip:6");
  const MemorySampleSource source(two_groups(5000, 1), layout.id, "r1");
  const SomatosensoryMap map = somatosensory_map(source, layout, 0);
  ASSERT_EQ(map.taxels.size(), 6u);
  EXPECT_EQ(map.samples, 5000);
  double within = 0.0, across = 1e300;
  for (size_t i = 0; i < 6; ++i)
    for (size_t j = i + 1; j < 6; ++j) {
      if ((i < 3) == (j < 3))
        within = std::max(within, distance(map, i, j));
      else
        across = std::min(across, distance(map, i, j));
    }
  EXPECT_LT(within * 5.0, across) << "within " << within << " across " << across;
  // Inside the body map's bounding box.
  double x0 = 1e300, x1 = -1e300;
  for (const Taxel& taxel : layout.taxels)
    x0 = std::min(x0, taxel.position.x), x1 = std::max(x1, taxel.position.x);
  for (const Point2& point : map.positions) {
    EXPECT_GE(point.x, x0 - 1e-9);
    EXPECT_LE(point.x, x1 + 1e-9);
  }
}

TEST(SomatosensoryMap, OnTheMapTaxelsLeaveTheBodyAndItsOutline) {
  SkinLayout layout = load_layout("strip:6");
  layout.body_outline = {{{0.0, 0.0}, {60.0, 0.0}, {60.0, 10.0}, {0.0, 10.0}}};
  const MemorySampleSource source(two_groups(2000, 2), layout.id, "r1");
  const SomatosensoryMap map = somatosensory_map(source, layout, 0);
  const SkinLayout moved = layout_on_map(layout, map);
  EXPECT_TRUE(moved.body_outline.empty());
  for (size_t k = 0; k < map.taxels.size(); ++k) {
    const Taxel& taxel = *moved.find_taxel(map.taxels[k]);
    EXPECT_DOUBLE_EQ(taxel.position.x, map.positions[k].x);
    EXPECT_EQ(taxel.shape, TaxelShape::kCircle);
  }
}

TEST(SomatosensoryMap, PooledSumsEqualOnePassAndGapsAreLeftOut) {
  const Stream stream = two_groups(3000, 2);
  const MemorySampleSource whole(stream, "strip:6", "r");
  CorrelationSums one(6), pooled(6);
  const std::vector<int> columns = {0, 1, 2, 3, 4, 5};
  one.add(whole, columns, 700);
  Stream first = stream, second = stream;
  first.samples = stream.samples.topRows(1200);
  second.samples = stream.samples.bottomRows(1800);
  pooled.add(MemorySampleSource(first, "strip:6", "a"), columns, 500);
  pooled.add(MemorySampleSource(second, "strip:6", "b"), columns, 8192);
  EXPECT_EQ(pooled.samples(), 3000);
  EXPECT_TRUE(one.correlation().isApprox(pooled.correlation(), 1e-9));
  // A NaN row (a damaged chunk read as a gap) does not poison the sums.
  Stream gappy = stream;
  gappy.samples(10, 2) = std::nanf("");
  CorrelationSums with_gap(6);
  with_gap.add(MemorySampleSource(gappy, "strip:6", "g"), columns);
  EXPECT_EQ(with_gap.samples(), 2999);
  EXPECT_TRUE(with_gap.correlation().allFinite());
  // A constant taxel correlates with nothing (and is placed far away by the clamp).
  Stream flat = stream;
  flat.samples.col(5).setConstant(2.0f);
  CorrelationSums constant(6);
  constant.add(MemorySampleSource(flat, "strip:6", "f"), columns);
  EXPECT_EQ(constant.correlation()(5, 0), 0.0);
  EXPECT_EQ(constant.correlation()(5, 5), 1.0);
}

TEST(SomatosensoryMap, CacheBesideTheRecordingIsUsedUntilItChanges) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                       ("somatosensory-cache-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  Recording recording;
  recording.id = "r1";
  recording.layout_id = "strip:6";
  recording.streams.push_back(two_groups(2000, 3));
  const std::string path = (folder / "r1.h5").string();
  write_recording(path, recording);
  const SkinLayout layout = load_layout("strip:6");
  const FileSampleSource source(path);
  EXPECT_FALSE(read_somatosensory_cache(path, "value"));
  const SomatosensoryMap map = somatosensory_map(source, layout, 0);
  ASSERT_TRUE(write_somatosensory_cache(path, map));
  EXPECT_EQ(somatosensory_cache_path(path, map.modality),
            (folder / ("r1.somatosensory-" + map.modality + ".json")).string());
  const auto cached = read_somatosensory_cache(path, map.modality);
  ASSERT_TRUE(cached);
  EXPECT_EQ(cached->taxels, map.taxels);
  EXPECT_DOUBLE_EQ(cached->positions[4].y, map.positions[4].y);
  // The recording rewritten: the cache is stale.
  std::filesystem::last_write_time(
      path, std::filesystem::last_write_time(path) + std::chrono::seconds(5));
  EXPECT_FALSE(read_somatosensory_cache(path, map.modality));
  // Too few taxels is an error naming the map.
  EXPECT_THROW(somatosensory_map(layout, 0, {1, 2}, Eigen::MatrixXd::Identity(2, 2)), Error);
  std::filesystem::remove_all(folder);
}

TEST(SomatosensoryMap, ACorpusPoolsItsRecordingsAndItsCacheKnowsWhichOnes) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                       ("somatosensory-corpus-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const Stream whole = two_groups(4000, 5);
  std::vector<std::string> files;
  for (int part = 0; part < 2; ++part) {
    Recording recording;
    recording.id = "r" + std::to_string(part);
    recording.layout_id = "strip:6";
    Stream stream = whole;
    stream.samples = whole.samples.middleRows(part * 2000, 2000);
    recording.streams.push_back(stream);
    files.push_back((folder / (recording.id + ".h5")).string());
    write_recording(files.back(), recording);
  }
  const SkinLayout layout = load_layout("strip:6");
  const SomatosensoryMap pooled = somatosensory_corpus_map(files, layout, 0);
  const SomatosensoryMap single =
      somatosensory_map(MemorySampleSource(whole, "strip:6", "w"), layout, 0);
  EXPECT_EQ(pooled.samples, 4000);
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_NEAR(pooled.positions[k].x, single.positions[k].x, 1e-6);
    EXPECT_NEAR(pooled.positions[k].y, single.positions[k].y, 1e-6);
  }
  const std::string cache =
      somatosensory_corpus_cache_path(folder.string(), "strip:6", pooled.modality);
  ASSERT_TRUE(write_somatosensory_corpus_cache(cache, files, pooled));
  EXPECT_TRUE(read_somatosensory_corpus_cache(cache, files));
  EXPECT_FALSE(read_somatosensory_corpus_cache(cache, {files[0]}));  // another corpus
  // A recording of another skin is named, not pooled.
  Recording other;
  other.id = "grid";
  other.layout_id = "grid:2x3";
  Stream stream = whole;
  stream.samples = whole.samples.topRows(100);
  stream.channels = {"r0c0", "r0c1", "r0c2", "r1c0", "r1c1", "r1c2"};
  other.streams.push_back(stream);
  const std::string other_path = (folder / "grid.h5").string();
  write_recording(other_path, other);
  try {
    somatosensory_corpus_map({files[0], other_path}, layout, 0);
    FAIL() << "pooled a recording of another skin";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("grid.h5"), std::string::npos) << error.what();
  }
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// Three body parts of six taxels in a row each (on the body map: parts side by side).
SkinLayout three_parts() {
  SkinLayout layout;
  layout.id = "three-parts";
  for (int64_t id = 0; id < 18; ++id) {
    Taxel taxel;
    taxel.id = id;
    taxel.body_part = std::string(1, static_cast<char>('a' + id / 6));
    taxel.position = {static_cast<double>(id), 0.0};
    layout.taxels.push_back(taxel);
  }
  return layout;
}

SomatosensoryMap map_of(const SkinLayout& layout, const std::vector<Point2>& positions) {
  SomatosensoryMap map;
  for (const Taxel& taxel : layout.taxels) map.taxels.push_back(taxel.id);
  map.positions = positions;
  return map;
}

TEST(MapBodyAgreement, AMapThatGathersEachBodyPartScoresOneAndChanceIsTheirShare) {
  const SkinLayout layout = three_parts();
  std::vector<Point2> gathered;
  for (int64_t id = 0; id < 18; ++id)  // each part a tight cluster, the clusters far apart
    gathered.push_back({100.0 * static_cast<double>(id / 6) + 0.1 * static_cast<double>(id % 6),
                        std::sin(static_cast<double>(id))});
  const MapBodyAgreement agreement = map_body_agreement(map_of(layout, gathered), layout);
  EXPECT_EQ(agreement.neighbours, 5);
  EXPECT_DOUBLE_EQ(agreement.same_part_share, 1.0);
  EXPECT_DOUBLE_EQ(agreement.chance_share, 3.0 * 6 * 5 / (18.0 * 17));
  EXPECT_GT(agreement.rank_correlation, 0.8);
}

TEST(MapBodyAgreement, EachPartsShareSaysWhichPartsGatherAndWhichAreMixed) {
  // Part a gathered far off; parts b and c alternate along one line, b at even x, c at odd.
  const SkinLayout layout = three_parts();
  std::vector<Point2> positions;
  for (int64_t id = 0; id < 6; ++id) positions.push_back({-500.0, static_cast<double>(id)});
  for (int64_t id = 6; id < 18; ++id)
    positions.push_back({id < 12 ? 2.0 * static_cast<double>(id - 6)          // b: 0, 2, ..., 10
                                 : 2.0 * static_cast<double>(id - 12) + 1.0,  // c: 1, 3, ..., 11
                         0.0});
  const MapBodyAgreement agreement = map_body_agreement(map_of(layout, positions), layout);
  ASSERT_EQ(agreement.part_share.size(), 3u);
  EXPECT_DOUBLE_EQ(agreement.part_share.at("a"), 1.0);
  EXPECT_LT(agreement.part_share.at("b"), 0.6);
  EXPECT_LT(agreement.part_share.at("c"), 0.6);
  // The whole share is the parts' shares weighted by their taxels (6 each here).
  EXPECT_NEAR(
      agreement.same_part_share,
      (agreement.part_share.at("a") + agreement.part_share.at("b") + agreement.part_share.at("c")) /
          3.0,
      1e-12);
}

TEST(MapBodyAgreement, TheBodyMapItselfCorrelatesOneAndAShuffledMapAboutChance) {
  const SkinLayout layout = three_parts();
  std::vector<Point2> body;
  for (const Taxel& taxel : layout.taxels) body.push_back(taxel.position);
  EXPECT_DOUBLE_EQ(map_body_agreement(map_of(layout, body), layout).rank_correlation, 1.0);
  // Taxels placed at random, over many draws: the share and correlation of chance.
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> place(0.0, 1.0);
  double share = 0.0, correlation = 0.0;
  constexpr int kDraws = 200;
  for (int draw = 0; draw < kDraws; ++draw) {
    std::vector<Point2> scattered;
    for (int k = 0; k < 18; ++k) scattered.push_back({place(random), place(random)});
    const MapBodyAgreement agreement = map_body_agreement(map_of(layout, scattered), layout);
    share += agreement.same_part_share / kDraws;
    correlation += agreement.rank_correlation / kDraws;
  }
  EXPECT_NEAR(share, 3.0 * 6 * 5 / (18.0 * 17), 0.03);
  EXPECT_NEAR(correlation, 0.0, 0.03);
}

TEST(MapBodyAgreement, TooFewTaxelsOrOneTheLayoutLacksIsRefused) {
  const SkinLayout layout = three_parts();
  SomatosensoryMap small = map_of(layout, std::vector<Point2>(18));
  small.taxels.resize(5);
  small.positions.resize(5);
  EXPECT_THROW(map_body_agreement(small, layout), Error);
  SomatosensoryMap stranger = map_of(layout, std::vector<Point2>(18));
  stranger.taxels[3] = 99;
  EXPECT_THROW(map_body_agreement(stranger, layout), Error);
}

}  // namespace
}  // namespace tactile
