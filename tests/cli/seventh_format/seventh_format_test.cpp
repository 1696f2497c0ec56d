// A seventh recording format from this folder alone (toy_format.cpp: one importer): found by
// its extension and by its first bytes, its options in `tactile import --help` and taken by
// the import, its fields in the workbench's Import dialog (typed through ImGui's input path)
// and its frames in the preview, with no file outside this folder naming it.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "tactile/formats/import.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "toy_format.h"

namespace tactile {
namespace {

class SeventhFormat : public ::testing::Test {
 protected:
  void SetUp() override {
    test::register_toy_format();
    std::ofstream(folder.file("session.toy")) << test::toy_file_text(8, 3);
  }
  test::TempFolder folder{"tactile-seventh-format"};
};

TEST_F(SeventhFormat, IsFoundByExtensionAndByItsFirstBytesAndPreviewedWithItsOptions) {
  ASSERT_NE(importer_for(folder.file("session.toy")), nullptr);
  EXPECT_EQ(importer_for(folder.file("session.toy"))->name(), test::kToyFormat);
  // The same bytes under a name no importer claims.
  std::ofstream(folder.file("session.dat")) << test::toy_file_text(8, 3);
  ASSERT_NE(importer_for(folder.file("session.dat")), nullptr);
  EXPECT_EQ(importer_for(folder.file("session.dat"))->name(), test::kToyFormat);

  FileImportOptions options;
  options.file = folder.file("session.dat");
  options.layout = "strip:3";
  options.values.set("--gain", "2");
  options.values.set("--skip", "1");
  const ImportPreview preview = preview_import(options, 3);
  ASSERT_EQ(preview.refusal, "");
  EXPECT_EQ(preview.format, "toy text");
  EXPECT_EQ(preview.samples, 7);
  ASSERT_EQ(preview.frames.size(), 3u);
  // Frame 1 (the first after the skip) holds 1, 2, 3, doubled.
  EXPECT_EQ(preview.frames[0], (std::vector<double>{2.0, 4.0, 6.0}));
  EXPECT_EQ(preview.classes, (std::vector<std::string>{"tap"}));

  // Its options are checked as the built-in ones: a wrong value and another format's flag are
  // refused by name.
  options.values.set("--skip", "1.5");
  EXPECT_EQ(preview_import(options).refusal, "--skip: \"1.5\" is not a whole number");
  options.values.erase("--skip");
  options.values.set("--rate", "10");
  EXPECT_NE(preview_import(options).refusal.find("--rate: is not an option of Toy text files"),
            std::string::npos)
      << preview_import(options).refusal;
}

TEST_F(SeventhFormat, ItsFlagsAreInTheCommandLinesHelpAndImport) {
  const test::CommandResult help =
      test::run_program("tactile-seventh-format", "import --help", folder);
  ASSERT_EQ(help.exit_code, 0) << help.err;
  EXPECT_NE(help.out.find("Toy text (.toy)"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--gain"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--no-classes"), std::string::npos) << help.out;
  // The project's own program knows nothing of it.
  const test::CommandResult plain = test::run_program("tactile", "import --help", folder);
  EXPECT_EQ(plain.out.find("--gain"), std::string::npos);

  const test::CommandResult imported = test::run_program(
      "tactile-seventh-format",
      "import " + folder.file("session.toy") + " --layout strip:3 --gain 0.5 --no-classes --out " +
          folder.file("toy.h5") + " --labels " + folder.file("labels.db"),
      folder);
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  const Recording recording = read_recording(folder.file("toy.h5"));
  const Stream& stream = recording.streams.front();
  ASSERT_EQ(stream.sample_count(), 8);
  EXPECT_FLOAT_EQ(stream.samples(7, 2), 0.5f * (7 + 2));
  // --no-classes: no ground truth, so no store either.
  EXPECT_FALSE(std::filesystem::exists(folder.file("labels.db")));

  const test::CommandResult refused =
      test::run_program("tactile-seventh-format",
                        "import " + folder.file("session.toy") +
                            " --layout strip:3 --gain -1 --out " + folder.file("refused.h5"),
                        folder);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_EQ(refused.err, "tactile: --gain: \"-1\" is not a positive number\n");
  EXPECT_FALSE(std::filesystem::exists(folder.file("refused.h5")));
}

TEST_F(SeventhFormat, TheImportDialogShowsItsFieldsAndPreviewsWhatTheyRead) {
  std::filesystem::create_directories(folder.file("ws"));
  const std::string script = test::write_script(
      folder,
      "wait 2\nmenu File/Import...\nclick item input:import/FILE\ntype " +
          folder.file("session.toy") +
          "\nclick item input:import/--layout\ntype strip:3\nclick item input:import/--gain\n"
          "type 3\nclick item input:import/--skip\ntype 2\nwait jobs\nstate @preview.json\n"
          "screenshot @dialog.png\nclick item checkbox:import/--no-classes\nwait jobs\n"
          "state @no-classes.json\nclick item button:import/Import\nwait jobs\nwait 2\n"
          "state @imported.json\n");
  const test::CommandResult run =
      test::run_program("tactile-workbench-headless-seventh-format",
                        folder.file("ws") + " --size 1300x860 --settings " +
                            folder.file("settings.json") + " --script " + script,
                        folder);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto state = [&](const std::string& name) {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  };
  const nlohmann::json preview = state("preview.json")["files"]["import"]["preview"];
  ASSERT_TRUE(preview.is_object()) << preview;
  EXPECT_EQ(preview["refusal"], "");
  EXPECT_EQ(preview["format"], "toy text");
  EXPECT_EQ(preview["samples"], 6);
  // Frame 2 (the first after the skip), tripled.
  EXPECT_EQ(preview["frames"][0], (std::vector<double>{6.0, 9.0, 12.0}));
  EXPECT_EQ(preview["classes"], (std::vector<std::string>{"tap"}));
  EXPECT_TRUE(state("no-classes.json")["files"]["import"]["preview"]["classes"].empty());
  // The import wrote what the preview showed, and the workbench opened it.
  const nlohmann::json imported = state("imported.json");
  EXPECT_EQ(imported["error"], "") << imported["error"];
  EXPECT_EQ(imported["recording"], "session") << imported["notice"];
  const Recording recording = read_recording(folder.file("ws/session.h5"));
  EXPECT_EQ(recording.streams.front().sample_count(), 6);
  EXPECT_FLOAT_EQ(recording.streams.front().samples(0, 1), 3.0f * (2 + 1));
}

}  // namespace
}  // namespace tactile
