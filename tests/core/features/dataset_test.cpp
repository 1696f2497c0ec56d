// Dataset CSV and ARFF: exact round trip, any CSV with a class column, errors naming
// file, line and column.
#include "tactile/features/dataset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "io_test_files.h"
#include "tactile/error.h"

namespace tactile {
namespace {

class DatasetFileTest : public ::testing::Test {
 protected:
  // A folder of this process's own: another test run on the machine may run the same test.
  void SetUp() override { folder_ = directory_.path(); }

  std::string file(const std::string& name) const { return (folder_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }
  static std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // The message of the tactile::Error that reading `text` throws.
  std::string read_error(const std::string& text) const {
    const std::string path = write("bad.csv", text);
    try {
      read_dataset_csv(path);
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  }

  static Dataset two_rows() {
    Dataset dataset;
    dataset.columns = {{"peak", "N"}, {"mean value", "N, mean over the segment"}};
    dataset.features.resize(2, 2);
    dataset.features << 0.1, 1.0 / 3.0, -2.5e-300, 123456789.123456789;
    dataset.classes = {"pat", "stroke, slow"};
    dataset.subjects = {"s01", ""};
    dataset.recordings = {"nao/s01", "nao/s02"};
    dataset.segment_ids = {7, 42};
    dataset.metadata = {{{"side", "front"}, {"note", " \"quoted\", spaced "}}, {{"trial", "3"}}};
    return dataset;
  }

  tactile::testing::TemporaryDirectory directory_;
  std::filesystem::path folder_;
};

TEST_F(DatasetFileTest, CsvRoundTripKeepsEveryBitAndEveryField) {
  const Dataset written = two_rows();
  write_dataset_csv(file("out.csv"), written);
  const Dataset read = read_dataset_csv(file("out.csv"));
  ASSERT_EQ(read.columns.size(), 2u);
  EXPECT_EQ(read.columns[0].name, "peak");
  EXPECT_EQ(read.columns[1].name, "mean value");
  ASSERT_EQ(read.rows(), 2);
  for (int64_t row = 0; row < 2; ++row)
    for (int64_t column = 0; column < 2; ++column)
      EXPECT_EQ(read.features(row, column), written.features(row, column));  // bit exact
  EXPECT_EQ(read.classes, written.classes);
  EXPECT_EQ(read.subjects, written.subjects);
  EXPECT_EQ(read.recordings, written.recordings);
  EXPECT_EQ(read.segment_ids, written.segment_ids);
  EXPECT_EQ(read.metadata, written.metadata);
  // Metadata keys come after the fixed columns, sorted.
  const std::string text = read_text(file("out.csv"));
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "peak,mean value,class,subject,recording,segment_id,note,side,trial");
}

TEST_F(DatasetFileTest, ReadsAnyCsvWithAClassColumnTellingFeaturesFromMetadata) {
  const std::string path = write("any.csv",
                                 "\xEF\xBB\xBFsubject,duration,place,area,class\r\n"
                                 "u1,0.5,head,12,pat\r\n"
                                 "u2,1.25,neck,7.5,slap\r\n"
                                 "\r\n");
  const Dataset dataset = read_dataset_csv(path);
  ASSERT_EQ(dataset.columns.size(), 2u);
  EXPECT_EQ(dataset.columns[0].name, "duration");
  EXPECT_EQ(dataset.columns[1].name, "area");
  ASSERT_EQ(dataset.rows(), 2);
  EXPECT_EQ(dataset.features(1, 0), 1.25);
  EXPECT_EQ(dataset.features(1, 1), 7.5);
  EXPECT_EQ(dataset.classes, (std::vector<std::string>{"pat", "slap"}));
  EXPECT_EQ(dataset.subjects, (std::vector<std::string>{"u1", "u2"}));
  EXPECT_EQ(dataset.metadata[1].at("place"), "neck");
  EXPECT_EQ(dataset.segment_ids, (std::vector<int64_t>{0, 0}));
  EXPECT_EQ(dataset.class_names(), (std::vector<std::string>{"pat", "slap"}));
}

TEST_F(DatasetFileTest, RaggedRowNamesItsLine) {
  const std::string message = read_error("a,b,class\n1,2,pat\n3,pat\n");
  EXPECT_NE(message.find("bad.csv:3"), std::string::npos) << message;
  EXPECT_NE(message.find("ragged"), std::string::npos) << message;
}

TEST_F(DatasetFileTest, NonNumericFeatureNamesLineAndColumn) {
  const std::string message = read_error("a,b,class\n1,2,pat\n3,four,pat\n");
  EXPECT_NE(message.find("bad.csv:3 column 2"), std::string::npos) << message;
}

TEST_F(DatasetFileTest, NanAndInfiniteFeaturesAreRefused) {
  EXPECT_NE(read_error("a,b,class\n1,nan,pat\n").find("bad.csv:2 column 2"), std::string::npos);
  EXPECT_NE(read_error("a,b,class\n1,2,pat\ninf,2,pat\n").find("bad.csv:3 column 1"),
            std::string::npos);
}

TEST_F(DatasetFileTest, MissingClassColumnEmptyClassAndNoRowsAreNamed) {
  EXPECT_NE(read_error("a,b,label\n1,2,pat\n").find("no 'class' column"), std::string::npos);
  EXPECT_NE(read_error("a,class\n1,\n").find("bad.csv:2 column 2"), std::string::npos);
  EXPECT_NE(read_error("a,b,class\n\n").find("no data rows"), std::string::npos);
  EXPECT_NE(read_error("").find("no header"), std::string::npos);
  EXPECT_NE(read_error("name,class\nx,pat\n").find("no numeric feature columns"),
            std::string::npos);
}

TEST_F(DatasetFileTest, OwnFilesKeepNumericMetadataAsMetadata) {
  Dataset dataset = two_rows();
  dataset.metadata = {{{"trial", "1"}}, {{"trial", "2"}}};
  write_dataset_csv(file("out.csv"), dataset);
  const Dataset read = read_dataset_csv(file("out.csv"));
  EXPECT_EQ(read.columns.size(), 2u);
  EXPECT_EQ(read.metadata[1].at("trial"), "2");
}

TEST_F(DatasetFileTest, WriterRefusesNonFiniteValuesAndLeavesNoFile) {
  Dataset dataset = two_rows();
  dataset.features(1, 0) = std::numeric_limits<double>::quiet_NaN();
  try {
    write_dataset_csv(file("out.csv"), dataset);
    FAIL() << "a NaN was written";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("row 2 feature 'peak'"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(write_dataset_arff(file("out.arff"), dataset, "r"), Error);
  EXPECT_TRUE(std::filesystem::is_empty(folder_));
}

TEST_F(DatasetFileTest, MetadataKeyNamedLikeAColumnIsRefused) {
  Dataset dataset = two_rows();
  dataset.metadata[0]["subject"] = "s01";
  EXPECT_THROW(write_dataset_csv(file("out.csv"), dataset), Error);
  EXPECT_FALSE(std::filesystem::exists(file("out.csv")));
}

TEST_F(DatasetFileTest, ArffHasNumericAttributesAQuotedNominalClassAndNoMetadata) {
  write_dataset_arff(file("out.arff"), two_rows(), "generic features");
  const std::string text = read_text(file("out.arff"));
  EXPECT_NE(text.find("@relation 'generic features'\n"), std::string::npos) << text;
  EXPECT_NE(text.find("@attribute peak numeric\n"), std::string::npos);
  EXPECT_NE(text.find("@attribute 'mean value' numeric\n"), std::string::npos);
  EXPECT_NE(text.find("@attribute class {pat,'stroke, slow'}\n"), std::string::npos) << text;
  EXPECT_NE(text.find("@data\n0.1,0.3333333333333333,pat\n"), std::string::npos) << text;
  EXPECT_NE(text.find("-2.5e-300,123456789.12345679,'stroke, slow'\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("nao/s01"), std::string::npos);  // recordings left out
  EXPECT_EQ(text.find("front"), std::string::npos);    // metadata left out
}

TEST_F(DatasetFileTest, ArffEscapesQuotesInNames) {
  Dataset dataset = two_rows();
  dataset.columns[0].name = "it's";
  dataset.classes[0] = "?";
  write_dataset_arff(file("out.arff"), dataset, "r");
  const std::string text = read_text(file("out.arff"));
  EXPECT_NE(text.find("@attribute 'it\\'s' numeric"), std::string::npos) << text;
  EXPECT_NE(text.find("{'?','stroke, slow'}"), std::string::npos) << text;
}

}  // namespace
}  // namespace tactile
