// The command line's file commands from the headless workbench's menus and dialogs, driven by
// scripts through ImGui's real input path: Open folder, Export labels and features (the same
// bytes as `tactile labels export` and `tactile features`), a save that asks before writing
// over a file, Import labels, the agreement report, Verify of a good and a damaged file,
// Upgrade of the open recording, and Escape closing each dialog.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "test_paths.h"

namespace tactile {
namespace {

class WorkbenchFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto made = test::run_program(
        "tactile",
        "simulate --skin fur --subjects 2 --repetitions 1 --seed 5 --out " + folder.file("ws"),
        folder);
    ASSERT_EQ(made.exit_code, 0) << made.err;
  }
  std::string recording() const { return folder.file("ws/fur-s01-t01.h5"); }
  std::string database() const { return folder.file("ws/labels.db"); }
  std::string script(const std::string& text) { return test::write_script(folder, text); }
  // The headless workbench on `open` ("" = nothing) playing `text`.
  test::CommandResult workbench(const std::string& open, const std::string& text) {
    return test::run_program("tactile-workbench-headless",
                             open + " --annotator ana --size 1300x860 --settings " +
                                 folder.file("settings.json") + " --script " + script(text),
                             folder);
  }
  test::CommandResult tactile(const std::string& arguments) {
    return test::run_program("tactile", arguments, folder);
  }
  nlohmann::json state(const std::string& name) {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }

  test::TempFolder folder{"tactile-workbench-files"};
};

TEST_F(WorkbenchFiles, EscapeClosesTheFileDialogAndTheNextClickWorks) {
  const auto run = workbench(
      recording(),
      "wait 2\nmenu File/Open...\nwait 1\nstate @browsing.json\nkey Escape\nwait 1\nstate "
      "@escaped.json\n"
      "menu View/Stacked lanes\nstate @clicked.json\n"
      "menu File/Import...\nwait 1\nkey Escape\nwait 1\nstate @import-closed.json\n"
      "menu File/Export labels...\nwait 1\nkey Escape\nmenu File/Export features...\nwait 1\nkey "
      "Escape\n"
      "menu Labels/Agreement report...\nwait 1\nkey Escape\nwait 1\nstate @all-closed.json\n"
      "menu File/Import...\nclick item button:import/Browse FILE\nwait 1\nkey Escape\nwait 1\n"
      "state @browser-over-import.json\nkey Escape\nwait 1\nstate @import-escaped.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json browsing = state("browsing.json")["files"]["browser"];
  ASSERT_TRUE(browsing.is_object());
  EXPECT_EQ(browsing["mode"], "open");
  EXPECT_EQ(browsing["directory"], folder.file("ws"));
  EXPECT_TRUE(state("escaped.json")["files"]["browser"].is_null());
  // The modal is gone: the next click reaches the menu.
  EXPECT_TRUE(state("clicked.json")["plot"]["stacked"].get<bool>());
  EXPECT_EQ(state("import-closed.json")["files"]["dialogs"], nlohmann::json::array());
  EXPECT_EQ(state("all-closed.json")["files"]["dialogs"], nlohmann::json::array());
  // Escape over a dialog closes the browser only; the next one closes the dialog.
  const nlohmann::json over = state("browser-over-import.json")["files"];
  EXPECT_TRUE(over["browser"].is_null());
  EXPECT_EQ(over["dialogs"], nlohmann::json::array({"import"}));
  EXPECT_EQ(state("import-escaped.json")["files"]["dialogs"], nlohmann::json::array());
}

TEST_F(WorkbenchFiles, OpenFolderMakesTheChosenFolderTheWorkspace) {
  // Nothing open; the folder chosen in the dialog: up from where it starts, then typed.
  const auto run =
      workbench("",
                "wait 2\nmenu File/Open folder...\nwait 1\nstate @choosing.json\nclick item "
                "browser:path\ntype " +
                    folder.file("ws") + "\nclick item browser:OK\nwait 2\nstate @opened.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(state("choosing.json")["files"]["browser"]["mode"], "folder");
  const nlohmann::json opened = state("opened.json");
  EXPECT_EQ(opened["workspace"], folder.file("ws"));
  EXPECT_EQ(opened["recording"], "fur-s01-t01");
  EXPECT_EQ(opened["workspace_files"], nlohmann::json::array({"fur-s01-t01.h5", "fur-s02-t01.h5"}));
  EXPECT_GT(opened["labels"].get<int>(), 0);
}

TEST_F(WorkbenchFiles, ElanAndLabelStudioExportsAreTheCommandLinesAndImportMapsTiers) {
  // An ELAN file of another lab's session: two annotators' tiers, a ground-truth tier.
  std::filesystem::copy_file(test::test_data_dir() + "/interop/session.eaf",
                             folder.file("session.eaf"));
  const auto run =
      workbench(recording(),
                "wait 2\nmenu File/Export labels...\nclick item radio:export-labels/ELAN\n"
                "click item button:export-labels/Export...\nwait 1\n"
                "click item browser:OK\nwait jobs\n"
                "menu File/Export labels...\nclick item radio:export-labels/Label Studio\n"
                "click item radio:export-labels/every recording\n"
                "click item button:export-labels/Export...\nclick item browser:OK\nwait jobs\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_EQ(tactile("labels export " + database() + " --eaf " + folder.file("cli.eaf") +
                    " --recording fur-s01-t01 --skin fur")
                .exit_code,
            0);
  EXPECT_TRUE(test::read_text(folder.file("ws/fur-s01-t01-labels.eaf")) ==
              test::read_text(folder.file("cli.eaf")));
  ASSERT_EQ(tactile("labels export " + database() + " --label-studio " + folder.file("cli.json"))
                .exit_code,
            0);
  EXPECT_TRUE(test::read_text(folder.file("ws/labels-label-studio.json")) ==
              test::read_text(folder.file("cli.json")));

  const auto import = workbench(
      recording(),
      "wait 2\nmenu Labels/Import labels...\nclick item browser:path\ntype " +
          folder.file("session.eaf") +
          "\nclick item browser:OK\nwait jobs\nwait 1\nstate @choosing.json\n"
          "click item checkbox:import-labels/ground-truth\n"
          "click item input:import-labels/lane Touch (Ben)\nkey Ctrl+A\ntype model:ben-model\n"
          "click item button:import-labels/Import\nwait jobs\nwait 1\nstate @imported.json\n");
  ASSERT_EQ(import.exit_code, 0) << import.err;

  // The tiers shown with their lanes; the open recording proposed for the labels.
  const nlohmann::json dialogs = state("choosing.json")["files"]["dialogs"];
  EXPECT_NE(std::find(dialogs.begin(), dialogs.end(), "import labels"), dialogs.end()) << dialogs;
  EXPECT_EQ(state("imported.json")["notice"],
            "imported 4 labels into " + folder.file("ws/labels.db"));
  EXPECT_EQ(state("imported.json")["labels"].get<int>(),
            state("choosing.json")["labels"].get<int>() + 4);
  // Ana's tier to her lane, Ben's to a model's, the unchecked ground-truth tier left out.
  const auto listed = tactile("labels export " + database() + " --csv " + folder.file("in.csv") +
                              " --recording fur-s01-t01 --source model");
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  const std::string models = test::read_text(folder.file("in.csv"));
  EXPECT_NE(models.find("ben-model"), std::string::npos) << models;
  EXPECT_NE(models.find("very short, maybe a tap"), std::string::npos) << models;
  ASSERT_EQ(tactile("labels export " + database() + " --csv " + folder.file("ana.csv") +
                    " --recording fur-s01-t01 --source manual")
                .exit_code,
            0);
  const std::string manual = test::read_text(folder.file("ana.csv"));
  EXPECT_NE(manual.find(",0.12,0.87,"), std::string::npos) << manual;
  EXPECT_EQ(manual.find("protocol"), std::string::npos) << manual;
}

TEST_F(WorkbenchFiles, ExportedLabelsAndFeaturesAreTheCommandLinesBytes) {
  const auto run = workbench(
      recording(),
      "wait 2\nmenu File/Export labels...\nclick item button:export-labels/Export...\nwait 1\n"
      "state @saving.json\nclick item browser:OK\nwait jobs\nstate @labels-csv.json\n"
      "menu File/Export labels...\nclick item radio:export-labels/JSON\n"
      "click item radio:export-labels/every recording\nclick item "
      "radio:export-labels/ground-truth\n"
      "click item button:export-labels/Export...\nclick item browser:OK\nwait jobs\n"
      "menu File/Export features...\nclick item radio:export-features/workspace\n"
      "click item button:export-features/Export...\nclick item browser:OK\nwait jobs\nstate "
      "@features.json\n"
      "menu File/Export features...\nclick item radio:export-features/this recording\n"
      "click item radio:export-features/ARFF\nclick item button:export-features/Export...\n"
      "click item browser:OK\nwait jobs\nstate @arff.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json saving = state("saving.json")["files"]["browser"];
  EXPECT_EQ(saving["mode"], "save");
  EXPECT_EQ(saving["directory"], folder.file("ws"));
  EXPECT_EQ(state("labels-csv.json")["notice"].get<std::string>().rfind(
                "wrote " + folder.file("ws/fur-s01-t01-labels.csv"), 0),
            0u);

  ASSERT_EQ(tactile("labels export " + database() + " --csv " + folder.file("cli.csv") +
                    " --recording fur-s01-t01")
                .exit_code,
            0);
  EXPECT_EQ(test::read_text(folder.file("ws/fur-s01-t01-labels.csv")),
            test::read_text(folder.file("cli.csv")));
  ASSERT_EQ(tactile("labels export " + database() + " --json " + folder.file("cli.json") +
                    " --source ground-truth")
                .exit_code,
            0);
  EXPECT_EQ(test::read_text(folder.file("ws/labels.json")),
            test::read_text(folder.file("cli.json")));
  EXPECT_NE(test::read_text(folder.file("cli.json")).find("fur-s02-t01"), std::string::npos);

  // Features of every fur recording of the store, and of the open one alone, as ARFF.
  EXPECT_EQ(state("features.json")["error"], "");
  const auto features = tactile("features --pipeline fur --labels " + database() + " --out " +
                                folder.file("cli.csv"));
  ASSERT_EQ(features.exit_code, 0) << features.err;
  // The command's line, naming the window's file.
  std::string line = features.out.substr(0, features.out.find('\n'));
  line = line.substr(0, line.rfind("-> ")) + "-> " + folder.file("ws/fur-fur.csv");
  EXPECT_EQ(state("features.json")["notice"], line);
  EXPECT_EQ(test::read_text(folder.file("ws/fur-fur.csv")),
            test::read_text(folder.file("cli.csv")));
  EXPECT_EQ(test::read_text(folder.file("ws/fur-fur.csv.log")),
            test::read_text(folder.file("cli.csv.log")));
  std::filesystem::create_directories(folder.file("one"));
  ASSERT_EQ(tactile("labels export " + database() + " --json " + folder.file("one/truth.json") +
                    " --recording fur-s01-t01")
                .exit_code,
            0);
  ASSERT_EQ(
      tactile("labels import " + folder.file("one/labels.db") + " " + folder.file("one/truth.json"))
          .exit_code,
      0);
  std::filesystem::copy_file(recording(), folder.file("one/fur-s01-t01.h5"));
  const auto arff = tactile("features --pipeline fur --labels " + folder.file("one/labels.db") +
                            " --out " + folder.file("one/cli.arff"));
  ASSERT_EQ(arff.exit_code, 0) << arff.err;
  EXPECT_EQ(state("arff.json")["error"], "");
  EXPECT_EQ(test::read_text(folder.file("ws/fur-s01-t01-fur.arff")),
            test::read_text(folder.file("one/cli.arff")));
}

TEST_F(WorkbenchFiles, ASaveOverAnExistingFileWaitsForOverwrite) {
  std::ofstream(folder.file("ws/fur-s01-t01-labels.csv")) << "mine\n";
  const auto run = workbench(
      recording(),
      "wait 2\nmenu File/Export labels...\nclick item button:export-labels/Export...\nclick item "
      "browser:OK\n"
      "wait 2\nstate @asked.json\nscreenshot @asked.png\nclick item browser:Cancel\nwait 1\n"
      "click item browser:OK\nwait 1\nclick item browser:Overwrite\nwait jobs\nstate "
      "@written.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json asked = state("asked.json");
  EXPECT_EQ(asked["files"]["browser"]["mode"], "save");  // still asking
  EXPECT_EQ(asked["jobs"], nlohmann::json::array());
  EXPECT_TRUE(state("written.json")["files"]["browser"].is_null());
  ASSERT_EQ(tactile("labels export " + database() + " --csv " + folder.file("cli.csv") +
                    " --recording fur-s01-t01")
                .exit_code,
            0);
  EXPECT_EQ(test::read_text(folder.file("ws/fur-s01-t01-labels.csv")),
            test::read_text(folder.file("cli.csv")));
}

TEST_F(WorkbenchFiles, LabelsImportAndTheAgreementReport) {
  // A recording without a store: its ground truth comes from a file `labels export` wrote.
  std::filesystem::create_directories(folder.file("bare"));
  std::filesystem::copy_file(recording(), folder.file("bare/fur-s01-t01.h5"));
  ASSERT_EQ(tactile("labels export " + database() + " --csv " + folder.file("truth.csv") +
                    " --recording fur-s01-t01")
                .exit_code,
            0);
  auto run = workbench(
      folder.file("bare/fur-s01-t01.h5"),
      "wait 2\nstate @before.json\nmenu Labels/Import labels...\nclick item browser:path\ntype " +
          folder.file("truth.csv") + "\nkey Enter\nwait jobs\nstate @imported.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(state("before.json")["labels"], 0);
  const nlohmann::json imported = state("imported.json");
  const auto listed = tactile("labels list " + database() + " --recording fur-s01-t01 --json");
  const size_t truth = nlohmann::json::parse(listed.out)["labels"].size();
  EXPECT_EQ(imported["labels"], truth);
  EXPECT_EQ(imported["notice"],
            "imported " + std::to_string(truth) + " labels into " + folder.file("bare/labels.db"));
  // A second lane (the skin's segmenter), then ground truth against it.
  run = workbench(
      recording(),
      "wait 2\nmenu Labels/Run segmenter/threshold\nwait jobs\nmenu Labels/Agreement report...\n"
      "click item radio:agreement/A/ground-truth\nclick item "
      "radio:agreement/B/segmenter:threshold\n"
      "click item button:agreement/Compute\nwait jobs\nwait 1\nstate @report.json\n"
      "screenshot @report.png\nclick item button:report/Save...\nclick item browser:OK\nwait 1\n"
      "state @saved.json\nkey Escape\nwait 1\nstate @closed.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto cli = tactile("labels agreement " + database() +
                           " --a ground-truth --b segmenter:threshold --recording fur-s01-t01");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  const nlohmann::json report = state("report.json")["files"]["report"];
  ASSERT_TRUE(report.is_object());
  EXPECT_EQ(report["title"], "Agreement: ground-truth vs segmenter:threshold");
  EXPECT_EQ(report["text"], cli.out);
  EXPECT_EQ(test::read_text(folder.file("ws/fur-s01-t01-agreement.txt")), cli.out);
  EXPECT_EQ(state("saved.json")["notice"], "wrote " + folder.file("ws/fur-s01-t01-agreement.txt"));
  EXPECT_TRUE(state("closed.json")["files"]["report"].is_null());
}

TEST_F(WorkbenchFiles, VerifyReportsAGoodAndADamagedFile) {
  std::filesystem::create_directories(folder.file("damaged"));
  const std::string damaged = folder.file("damaged/fur-s02-t01.h5");
  std::filesystem::copy_file(folder.file("ws/fur-s02-t01.h5"), damaged);
  {
    const auto size = std::filesystem::file_size(damaged);
    std::fstream file(damaged, std::ios::binary | std::ios::in | std::ios::out);
    file.seekg(static_cast<std::streamoff>(size / 2));
    char byte = 0;
    file.get(byte);
    file.seekp(static_cast<std::streamoff>(size / 2));
    file.put(static_cast<char>(byte ^ 0x01));
  }
  const auto run = workbench(
      recording(),
      "wait 2\nmenu File/Verify/Open recording and its labels\nwait jobs\nwait 1\nstate "
      "@good.json\n"
      "menu File/Verify/File...\nclick item browser:path\ntype " +
          damaged +
          "\nkey Enter\nwait jobs\nwait 1\nstate @damaged.json\nscreenshot @verify.png\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json good = state("good.json");
  EXPECT_EQ(good["files"]["report"]["text"],
            "verified 1 recording(s) and 1 label store(s): no problems\n");
  EXPECT_EQ(good["error"], "");
  const auto cli = tactile("verify " + damaged);
  ASSERT_EQ(cli.exit_code, 1);
  const nlohmann::json bad = state("damaged.json");
  EXPECT_EQ(bad["files"]["report"]["text"], cli.out + cli.err);
  EXPECT_EQ(bad["files"]["report"]["text"].get<std::string>().rfind(damaged + ":/streams/skin/", 0),
            0u);
  EXPECT_NE(bad["error"].get<std::string>().find("problem(s)"), std::string::npos) << bad["error"];
}

TEST_F(WorkbenchFiles, UpgradeRewritesTheOpenRecordingAndOpensItAgain) {
  std::filesystem::create_directories(folder.file("old"));
  const std::string old_recording = folder.file("old/fur-s01-t01.h5");
  std::filesystem::copy_file(test::test_data_dir() + "/format_v1/fur-s01-t01.h5", old_recording);
  std::filesystem::copy_file(test::test_data_dir() + "/format_v1/labels.db",
                             folder.file("old/labels.db"));
  ASSERT_EQ(tactile("export " + old_recording + " --csv " + folder.file("before.csv")).exit_code,
            0);
  const auto run =
      workbench(old_recording,
                "wait 2\nstate @before.json\nmenu File/Upgrade/Open recording and its labels\n"
                "wait jobs\nwait 2\nstate @after.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json after = state("after.json");
  // The workbench opened the store (which brings a schema 1 store up to date); the recording
  // is the upgrade's.
  EXPECT_EQ(
      after["files"]["report"]["text"],
      old_recording + ": format 1 -> 2\n" + folder.file("old/labels.db") + ": already schema 4\n");
  EXPECT_EQ(after["error"], "");
  EXPECT_EQ(after["path"], old_recording);
  EXPECT_EQ(after["labels"], state("before.json")["labels"]);
  const auto verified = tactile("verify " + folder.file("old"));
  EXPECT_EQ(verified.exit_code, 0) << verified.out << verified.err;
  ASSERT_EQ(tactile("export " + old_recording + " --csv " + folder.file("after.csv")).exit_code, 0);
  EXPECT_EQ(test::read_text(folder.file("before.csv")), test::read_text(folder.file("after.csv")));
}

}  // namespace
}  // namespace tactile
