// LabelStore on disk: exports, bad database files, a killed writer, two writers.
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "label_store_fixture.h"
#include "tactile/error.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {
namespace {

//---- Exports

TEST_F(LabelStoreTest, CsvExportQuotesAwkwardFieldsPerRfc4180) {
  LabelStore store(path_);
  Label awkward = make_label("r1", 0.5, 1.25, "pat");
  awkward.note = "he said \"stop\", then\nleft";
  awkward.confidence = 0.1;
  const int64_t id = store.add(awkward);
  const Label stored = *store.get(id);
  const std::string out = (directory_ / "labels.csv").string();
  store.export_csv(out);
  EXPECT_EQ(
      read_text(out),
      "id,recording,t0,t1,region,class,annotator,source,confidence,note,created,modified\r\n" +
          std::to_string(id) + ",r1,0.5,1.25,all,pat,ana,manual,0.1," +
          "\"he said \"\"stop\"\", then\nleft\"," + stored.created + "," + stored.modified +
          "\r\n");
}

TEST_F(LabelStoreTest, CsvExportKeepsOnlyFilteredLabels) {
  LabelStore store(path_);
  store.add(make_label("r1", 0.0, 1.0, "pat"));
  store.add(make_label("r2", 0.0, 1.0, "poke"));
  store.add(make_label("r2", 1.0, 2.0, "rub"));
  LabelFilter filter;
  filter.recording = "r2";
  const std::string out = (directory_ / "r2.csv").string();
  store.export_csv(out, filter);
  const std::string text = read_text(out);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);
  EXPECT_EQ(text.find(",pat,"), std::string::npos);
  EXPECT_NE(text.find(",rub,"), std::string::npos);
}

TEST_F(LabelStoreTest, JsonExportHasEveryFieldOfEveryLabel) {
  LabelStore store(path_);
  Label first = make_label("r1", 0.5, 1.0, "stroke");
  first.region = "head";
  first.source = LabelSource::kGroundTruth;
  first.confidence = 0.8;
  first.note = "a \"quoted\"\nnote";
  const int64_t id = store.add(first);
  store.add(make_label("r1", 2.0, 3.0, "pat"));
  const std::string out = (directory_ / "labels.json").string();
  store.export_json(out);
  const nlohmann::json document = nlohmann::json::parse(read_text(out));
  ASSERT_EQ(document.at("labels").size(), 2u);
  const nlohmann::json& label = document["labels"][0];
  EXPECT_EQ(label.size(), 12u);
  EXPECT_EQ(label.at("id"), id);
  EXPECT_EQ(label.at("recording"), "r1");
  EXPECT_EQ(label.at("t0"), 0.5);
  EXPECT_EQ(label.at("t1"), 1.0);
  EXPECT_EQ(label.at("region"), "head");
  EXPECT_EQ(label.at("class"), "stroke");
  EXPECT_EQ(label.at("annotator"), "ana");
  EXPECT_EQ(label.at("source"), "ground-truth");
  EXPECT_EQ(label.at("confidence"), 0.8);
  EXPECT_EQ(label.at("note"), "a \"quoted\"\nnote");
  EXPECT_EQ(label.at("created"), store.get(id)->created);
  EXPECT_EQ(label.at("modified"), store.get(id)->modified);
  EXPECT_EQ(document["labels"][1].at("class"), "pat");
}

TEST_F(LabelStoreTest, ExportToUnwritablePathThrowsAndLeavesNoFile) {
  LabelStore store(path_);
  store.add(make_label("r1", 0.0, 1.0, "pat"));
  const std::string missing_directory = (directory_ / "no" / "such" / "labels.csv").string();
  try {
    store.export_csv(missing_directory);
    FAIL();
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), missing_directory);
  }
  // Renaming over a directory fails after the temporary was written: it must go.
  const std::filesystem::path occupied = directory_ / "occupied";
  std::filesystem::create_directory(occupied);
  std::filesystem::create_directory(occupied / "keep");
  EXPECT_THROW(store.export_json(occupied.string()), Error);
  int entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory_)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
    ++entries;
  }
  EXPECT_GE(entries, 2);  // the database and "occupied"
}

TEST_F(LabelStoreTest, ExportReplacesAnExistingFileWhole) {
  LabelStore store(path_);
  store.add(make_label("r1", 0.0, 1.0, "pat"));
  const std::string out = (directory_ / "labels.json").string();
  std::ofstream(out) << std::string(10000, 'x');
  store.export_json(out);
  EXPECT_EQ(nlohmann::json::parse(read_text(out)).at("labels").size(), 1u);
}

//---- Opening

TEST_F(LabelStoreTest, RandomBytesAreNotADatabase) {
  {
    std::mt19937 generator(7);
    std::ofstream file(path_, std::ios::binary);
    for (int i = 0; i < 8192; ++i) file.put(static_cast<char>(generator() & 0xff));
  }
  try {
    LabelStore store(path_);
    FAIL() << "opened random bytes";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path_);
    EXPECT_NE(error.message().find("not a SQLite database"), std::string::npos) << error.what();
  }
}

TEST_F(LabelStoreTest, NewerSchemaVersionIsRefused) {
  { LabelStore store(path_); }
  sqlite3* database = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &database), SQLITE_OK);
  ASSERT_EQ(
      sqlite3_exec(database, "UPDATE store_schema SET version = 99", nullptr, nullptr, nullptr),
      SQLITE_OK);
  sqlite3_close(database);
  try {
    LabelStore store(path_);
    FAIL() << "opened a newer schema";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path_);
    EXPECT_NE(error.message().find("version 99"), std::string::npos) << error.what();
  }
}

TEST_F(LabelStoreTest, ForeignSqliteDatabaseIsRefused) {
  sqlite3* database = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &database), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(database, "CREATE TABLE photos (id INTEGER)", nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(database);
  EXPECT_THROW(LabelStore store(path_), Error);
}

TEST_F(LabelStoreTest, ExistingModeDoesNotCreateAMissingDatabase) {
  try {
    LabelStore store(path_, LabelStore::OpenMode::kExisting);
    FAIL();
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path_);
  }
  EXPECT_FALSE(std::filesystem::exists(path_));
}

TEST_F(LabelStoreTest, MovedStoreKeepsWorking) {
  LabelStore first(path_);
  const int64_t id = first.add(make_label("r1", 0.0, 1.0, "pat"));
  LabelStore second = std::move(first);
  EXPECT_TRUE(second.get(id));
  EXPECT_EQ(second.path(), path_);
  EXPECT_EQ(second.integrity_check(), "ok");
}

//---- Processes

bool read_exactly(int descriptor, void* buffer, size_t size) {
  auto* bytes = static_cast<char*>(buffer);
  while (size > 0) {
    const ssize_t got = read(descriptor, bytes, size);
    if (got <= 0) return false;
    bytes += got;
    size -= static_cast<size_t>(got);
  }
  return true;
}

TEST_F(LabelStoreTest, EveryAddThatReturnedSurvivesSigkill) {
  { LabelStore store(path_); }  // no connection may cross fork()
  int channel[2];
  ASSERT_EQ(pipe(channel), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(channel[0]);
    try {
      LabelStore store(path_);
      for (int i = 0; i < 1000000; ++i) {
        const int64_t id = store.add(make_label("r1", i, i + 0.5, "pat", "writer"));
        if (write(channel[1], &id, sizeof(id)) != sizeof(id)) _exit(3);
      }
    } catch (...) {
      _exit(2);
    }
    _exit(0);
  }
  close(channel[1]);
  std::vector<int64_t> reported;
  int64_t id = 0;
  while (reported.size() < 40 && read_exactly(channel[0], &id, sizeof(id))) reported.push_back(id);
  ASSERT_EQ(reported.size(), 40u) << "the writer stopped early";
  kill(child, SIGKILL);
  // Ids written before the kill are still in the pipe.
  while (read_exactly(channel[0], &id, sizeof(id))) reported.push_back(id);
  close(channel[0]);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);

  LabelStore reopened(path_);
  EXPECT_EQ(reopened.integrity_check(), "ok");
  for (int64_t reported_id : reported) EXPECT_TRUE(reopened.get(reported_id)) << reported_id;
  EXPECT_GE(reopened.count(), static_cast<int64_t>(reported.size()));
  // The killed writer left a usable store.
  EXPECT_GT(reopened.add(make_label("r2", 0.0, 1.0, "pat")), reported.back());
}

// Both writers fork before the database exists, so they also race to create it.
TEST_F(LabelStoreTest, TwoProcessesWritingAtOnceLoseNothing) {
  std::vector<pid_t> children;
  for (int writer = 0; writer < 2; ++writer) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        LabelStore store(path_);
        const std::string recording = "writer" + std::to_string(writer);
        for (int i = 0; i < 200; ++i) store.add(make_label(recording, i, i + 1.0, "pat"));
      } catch (const std::exception& error) {
        fprintf(stderr, "writer %d: %s\n", writer, error.what());
        _exit(1);
      }
      _exit(0);
    }
    children.push_back(child);
  }
  for (pid_t child : children) {
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
  }
  LabelStore store(path_);
  EXPECT_EQ(store.count(), 400);
  EXPECT_EQ(store.count("writer0"), 200);
  EXPECT_EQ(store.count("writer1"), 200);
  EXPECT_EQ(store.integrity_check(), "ok");
  std::set<int64_t> ids;
  for (const Label& label : store.list()) ids.insert(label.id);
  EXPECT_EQ(ids.size(), 400u);
  EXPECT_EQ(store.journal().size(), 400u);
}

}  // namespace
}  // namespace tactile
