// File > Import in the headless workbench, driven by scripts through ImGui's real input path:
// one file of each format of docs/IMPORT.md typed or browsed into the dialog, the preview of
// its first frames, the recording it opens and the ground truth it stores, compared with what
// `tactile import` writes from the same options; refusals shown as the command line words them.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "edf_test_files.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "test_paths.h"

namespace tactile {
namespace {

const std::string kImportData = tactile::test::test_data_dir() + "/import/";
const std::string kIoData = tactile::test::test_data_dir() + "/io/";

// One format: the file, the dialog's fields (flag, text), its checkboxes, and the same
// options as `tactile import` takes them.
struct ImportCase {
  std::string name;
  std::string file;
  std::vector<std::pair<std::string, std::string>> fields;
  std::vector<std::string> checkboxes;
  std::string cli;
  std::string recording;  // the id the import gives it
  int64_t samples = 0;    // in the recording opened
  size_t labels = 0;      // ground truth stored for it
};

class WorkbenchImport : public ::testing::Test {
 protected:
  void SetUp() override {
    // A long CSV with a class column, written here: strip:3, 12 samples at 10 Hz.
    std::ofstream csv(folder.file("touches.csv"));
    csv << "t,c0,c1,c2,gesture\n";
    for (int k = 0; k < 12; ++k)
      csv << k / 10.0 << "," << k << "," << 2 * k << ",0.5,"
          << (k < 4   ? "none"
              : k < 8 ? "tap"
                      : "rub")
          << "\n";
    csv.close();
    testing::write_edf_test_file(folder.file("session.edf"), testing::edf_test_plus_file());
    std::filesystem::create_directories(folder.file("ws"));
  }
  std::string script(const std::string& text) { return test::write_script(folder, text); }
  // The workbench on the empty workspace `ws`: imports land there.
  test::CommandResult workbench(const std::string& text) {
    return test::run_program("tactile-workbench-headless",
                             folder.file("ws") + " --size 1300x860 --settings " +
                                 folder.file("settings.json") + " --script " + script(text),
                             folder);
  }
  nlohmann::json state(const std::string& name) {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }
  // The script lines that fill the dialog's fields for `c`.
  static std::string fill(const ImportCase& c) {
    // The checkboxes first: --wide shows the fields of the wide shape.
    std::string text;
    for (const std::string& flag : c.checkboxes)
      text += "click item checkbox:import/" + flag + "\n";
    for (const auto& [flag, value] : c.fields)
      text += "click item input:import/" + flag + "\ntype " + value + "\n";
    return text;
  }

  test::TempFolder folder{"tactile-workbench-import"};
};

TEST_F(WorkbenchImport, EachFormatImportsFromTheDialogAsTheCommandLineDoes) {
  const std::vector<ImportCase> cases = {
      {"long CSV with a class column",
       folder.file("touches.csv"),
       {{"--layout", "strip:3"}, {"--class-column", "gesture"}},
       {},
       "--layout strip:3 --class-column gesture",
       "touches",
       12,
       2},
      {"long CSV split by groups",
       kImportData + "table.csv",
       {{"--layout", "strip:4"},
        {"--class-column", "gesture"},
        {"--group-columns", "subject,capture"}},
       {},
       "--layout strip:4 --class-column gesture --group-columns subject,capture",
       "table-s1-1",
       20,
       1},
      {"wide CSV",
       kIoData + "wide_strip2.csv",
       {{"--layout", "strip:2"},
        {"--rate", "10"},
        {"--samples-per-capture", "3"},
        {"--labels-file", kIoData + "wide_strip2_labels.csv"},
        {"--class-names", "poke,pat,slap"}},
       {"--wide"},
       "--layout strip:2 --wide --rate 10 --samples-per-capture 3 --labels-file " + kIoData +
           "wide_strip2_labels.csv --class-names poke,pat,slap",
       "wide_strip2",
       9,
       3},
      {".npy",
       kImportData + "frames.npy",
       {{"--layout", "grid:4x4"}, {"--rate", "100"}},
       {},
       "--layout grid:4x4 --rate 100",
       "frames",
       50,
       0},
      {".npz",
       kImportData + "frames.npz",
       {{"--layout", "grid:4x4"},
        {"--rate", "100"},
        {"--dataset", "pressure"},
        {"--class-array", "gesture"}},
       {},
       "--layout grid:4x4 --rate 100 --dataset pressure --class-array gesture",
       "frames",
       50,
       2},
      {".json",
       kImportData + "frames.json",
       {{"--layout", "grid:4x4"},
        {"--rate", "100"},
        {"--key", "data.frames"},
        {"--class-array", "data.gesture"}},
       {},
       "--layout grid:4x4 --rate 100 --key data.frames --class-array data.gesture",
       "frames",
       50,
       2},
      {"another program's .h5",
       kImportData + "foreign.h5",
       {{"--layout", "grid:4x4"},
        {"--rate", "100"},
        {"--dataset", "/sensors/pressure"},
        {"--class-array", "/sensors/gesture"}},
       {},
       "--layout grid:4x4 --rate 100 --dataset /sensors/pressure --class-array /sensors/gesture",
       "foreign",
       50,
       2},
      {"EDF+ with annotations",
       folder.file("session.edf"),
       {{"--layout", "strip:4"}, {"--signals", "Fz,Cz,Pz,Oz"}, {"--annotation-seconds", "0.5"}},
       {},
       "--layout strip:4 --signals Fz,Cz,Pz,Oz --annotation-seconds 0.5",
       "session",
       300,
       3},
      {"XDF with a markers stream",
       tactile::test::test_data_dir() + "/interop/glove_session.xdf",
       {{"--layout", "strip:8"}, {"--stream", "type:Tactile"}, {"--markers", "Touches"}},
       {},
       "--layout strip:8 --stream type:Tactile --markers Touches",
       "glove_session",
       60,
       4},
  };
  for (size_t k = 0; k < cases.size(); ++k) {
    const ImportCase& c = cases[k];
    SCOPED_TRACE(c.name);
    std::filesystem::remove_all(folder.file("ws"));
    std::filesystem::create_directories(folder.file("ws"));
    const std::string name = "import-" + std::to_string(k);
    const auto run =
        workbench("wait 2\nmenu File/Import...\nclick item input:import/FILE\ntype " + c.file +
                  "\n" + fill(c) + "wait jobs\nstate @" + name + "-preview.json\n" +
                  "click item button:import/Import\nwait jobs\nwait 2\nstate @" + name + ".json\n");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    // The preview read what the import then wrote.
    const nlohmann::json preview = state(name + "-preview.json")["files"]["import"]["preview"];
    ASSERT_TRUE(preview.is_object()) << preview;
    EXPECT_EQ(preview["refusal"], "") << preview;
    EXPECT_FALSE(preview["frames"].empty());
    EXPECT_EQ(preview["frames"].size(), std::min<size_t>(10, preview["samples"].get<size_t>()));
    EXPECT_EQ(preview["classes"].empty(), c.labels == 0) << preview;
    // The recording opens, in the workspace, with its ground truth.
    const nlohmann::json after = state(name + ".json");
    EXPECT_EQ(after["error"], "") << after["error"];
    EXPECT_EQ(after["recording"], c.recording) << after["notice"];
    EXPECT_EQ(after["files"]["dialogs"].size(), 0u);
    const std::string opened = after["path"];
    EXPECT_EQ(std::filesystem::path(opened).parent_path().filename(),
              c.name == "long CSV split by groups" ? "table" : "ws");  // the group's folder
    EXPECT_EQ(RecordingFile(opened).stream("skin").sample_count, c.samples);
    const std::vector<std::string> listed = after["workspace_files"];
    EXPECT_NE(std::find(listed.begin(), listed.end(),
                        std::filesystem::relative(opened, folder.file("ws")).string()),
              listed.end());
    size_t truth = 0;
    for (const auto& lane : after["lanes"])
      if (lane["id"] == "ground-truth") truth = lane["labels"];
    EXPECT_EQ(truth, c.labels);
    // The command line's import of the same file with the same options: the same samples and
    // labels.
    const bool grouped = c.name == "long CSV split by groups";
    const std::string cli_folder = folder.file("cli-" + name);
    std::filesystem::create_directories(cli_folder);
    const std::string cli_out = grouped ? cli_folder : cli_folder + "/" + c.recording + ".h5";
    const auto cli = test::run_program("tactile",
                                       "import " + c.file + " " + c.cli + " --out " + cli_out +
                                           " --labels " + cli_folder + "/labels.db",
                                       folder);
    ASSERT_EQ(cli.exit_code, 0) << cli.err;
    const std::string cli_file = grouped ? cli_out + "/" + c.recording + ".h5" : cli_out;
    const Recording window_recording = read_recording(opened);
    const Recording cli_recording = read_recording(cli_file);
    // Bit for bit: the XDF recording's dropout is NaN, which == never equals.
    const SampleMatrix& window_samples = window_recording.streams.front().samples;
    const SampleMatrix& cli_samples = cli_recording.streams.front().samples;
    ASSERT_EQ(window_samples.size(), cli_samples.size());
    EXPECT_EQ(std::memcmp(window_samples.data(), cli_samples.data(),
                          sizeof(float) * static_cast<size_t>(window_samples.size())),
              0);
    EXPECT_EQ(window_recording.metadata, cli_recording.metadata);
    LabelFilter filter;
    filter.recording = c.recording;
    // The window's default store: labels.db beside what it wrote.
    const std::vector<Label> window_labels =
        LabelStore((std::filesystem::path(opened).parent_path() / "labels.db").string())
            .list(filter);
    std::vector<Label> cli_labels;
    if (c.labels > 0)
      cli_labels = LabelStore(folder.file("cli-" + name + "/labels.db")).list(filter);
    ASSERT_EQ(window_labels.size(), cli_labels.size());
    for (size_t l = 0; l < window_labels.size(); ++l) {
      EXPECT_EQ(window_labels[l].class_name, cli_labels[l].class_name);
      EXPECT_EQ(window_labels[l].t0, cli_labels[l].t0);
      EXPECT_EQ(window_labels[l].t1, cli_labels[l].t1);
    }
  }
}

TEST_F(WorkbenchImport, TheFileComesFromTheBrowserAndARefusalNamesTheOption) {
  // FILE from the browser; an .npz of two arrays is refused until --dataset names one, as
  // `tactile import` refuses it; an array without --rate names --rate.
  const auto run = workbench(
      "wait 2\nmenu File/Import...\nclick item button:import/Browse FILE\nclick item "
      "browser:path\ntype " +
      kImportData +
      "frames.npz\nkey Enter\nwait 2\nclick item input:import/--layout\ntype grid:4x4\nwait jobs\n"
      "state @no-rate.json\nclick item input:import/--rate\ntype 100\nwait jobs\nstate "
      "@two-arrays.json\n"
      "screenshot @refusal.png\nclick item button:import/Import\nwait jobs\nstate @refused.json\n"
      "click item input:import/--dataset\ntype pressure\nwait jobs\nstate @named.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json no_rate = state("no-rate.json")["files"]["import"];
  EXPECT_EQ(no_rate["file"], kImportData + "frames.npz");
  EXPECT_EQ(no_rate["preview"]["refusal"], "--rate: is needed for an array (it carries no time)");
  const nlohmann::json two = state("two-arrays.json")["files"]["import"]["preview"];
  const auto cli =
      test::run_program("tactile",
                        "import " + kImportData + "frames.npz --layout grid:4x4 --rate 100 --out " +
                            folder.file("x.h5"),
                        folder);
  ASSERT_NE(cli.exit_code, 0);
  EXPECT_EQ("tactile: " + two["refusal"].get<std::string>() + "\n", cli.err);
  // Import pressed anyway: refused with the same words, nothing written, the dialog stays.
  const nlohmann::json refused = state("refused.json");
  EXPECT_EQ(refused["files"]["import"]["failure"], two["refusal"]);
  EXPECT_EQ(refused["files"]["dialogs"], nlohmann::json::array({"import"}));
  EXPECT_FALSE(std::filesystem::exists(folder.file("ws/frames.h5")));
  const nlohmann::json named = state("named.json")["files"]["import"]["preview"];
  EXPECT_EQ(named["refusal"], "");
  EXPECT_EQ(named["shape"], nlohmann::json::array({50, 4, 4}));
  EXPECT_EQ(named["channels"].size(), 16u);
  EXPECT_EQ(named["samples"], 50);
  EXPECT_EQ(named["classes"], nlohmann::json::array());  // no --class-array yet
}

}  // namespace
}  // namespace tactile
