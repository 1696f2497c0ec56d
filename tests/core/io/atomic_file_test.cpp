// Whole-file atomic writes (tactile/io/atomic_file.h): the target is the old file or the new
// one, and no temporary file stays behind.
#include "tactile/io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "io_test_files.h"
#include "tactile/error.h"

namespace tactile {
namespace {

using testing::read_text;
using testing::TemporaryDirectory;
using testing::write_text;

std::vector<std::string> names_in(const TemporaryDirectory& directory) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory.path()))
    names.push_back(entry.path().filename().string());
  return names;
}

TEST(AtomicFile, AfterSuccessTheFolderHoldsOnlyTheTarget) {
  TemporaryDirectory directory;
  const std::string path = directory.file("report.json");
  write_file_atomically(path, "first\n", "report");
  write_file_atomically(path, "second\n", "report");
  EXPECT_EQ(read_text(path), "second\n");
  EXPECT_EQ(names_in(directory), std::vector<std::string>{"report.json"});
}

TEST(AtomicFile, AWriterGivenATemporaryPathReplacesTheTargetWhole) {
  TemporaryDirectory directory;
  const std::string path = directory.file("recording.h5");
  write_text(path, "old");
  std::string given;
  write_file_atomically(
      path,
      [&](const std::string& temporary) {
        given = temporary;
        EXPECT_FALSE(std::filesystem::exists(temporary));  // libraries may insist on a new file
        write_text(temporary, "new");
      },
      "recording");
  EXPECT_NE(given, path);
  EXPECT_EQ(std::filesystem::path(given).parent_path(), directory.path());
  EXPECT_EQ(read_text(path), "new");
  EXPECT_EQ(names_in(directory), std::vector<std::string>{"recording.h5"});
}

TEST(AtomicFile, AThrowingWriterLeavesTheTargetUnchangedAndNoTemporary) {
  TemporaryDirectory directory;
  const std::string path = directory.file("labels.csv");
  write_text(path, "old contents\n");
  EXPECT_THROW(write_file_atomically(
                   path,
                   [&](const std::string& temporary) {
                     write_text(temporary, "half of the new");
                     throw std::runtime_error("the writer failed");
                   },
                   "label export"),
               std::runtime_error);
  EXPECT_EQ(read_text(path), "old contents\n");
  EXPECT_EQ(names_in(directory), std::vector<std::string>{"labels.csv"});
}

TEST(AtomicFile, AFailedRenameNamesThePathAndLeavesNoTemporary) {
  TemporaryDirectory directory;
  // A folder with an entry cannot be replaced by a file: the rename fails after the write.
  const std::string path = directory.file("occupied");
  std::filesystem::create_directories(directory.path() / "occupied" / "keep");
  try {
    write_file_atomically(path, "text", "settings");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path);
    EXPECT_EQ(error.message().rfind("cannot replace the settings: ", 0), 0u) << error.message();
  }
  EXPECT_TRUE(std::filesystem::is_directory(directory.path() / "occupied" / "keep"));
  EXPECT_EQ(names_in(directory), std::vector<std::string>{"occupied"});
}

TEST(AtomicFile, AMissingFolderIsAnErrorNamingThePath) {
  TemporaryDirectory directory;
  const std::string path = directory.file("no/such/folder/file.txt");
  try {
    write_file_atomically(path, "text", "log");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path);
    EXPECT_EQ(error.message(), "cannot write the log: No such file or directory");
  }
  EXPECT_TRUE(names_in(directory).empty());
  // A file where a folder should be: an error too, not a search for a free name.
  write_text(directory.file("plain"), "x");
  EXPECT_THROW(write_file_atomically(directory.file("plain/file.txt"), "text", "log"), Error);
}

}  // namespace
}  // namespace tactile
