// The importers behind `tactile import` (formats/importer.h): the option values as given, the
// checks every format's options get, the flags the command line makes of them, and a file
// found by its extension or by its first bytes.
#include "tactile/formats/importer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "tactile/error.h"
#include "temp_folder.h"
#include "test_paths.h"

namespace tactile {
namespace {

const RecordingImporter& importer_named(const std::string& name) {
  for (const RecordingImporter* importer : importers())
    if (importer->name() == name) return *importer;
  throw Error(name, "no such importer");
}

TEST(ImportValues, ReadNumbersCountsListsAndSwitchesAsTyped) {
  ImportValues values;
  values.set("--rate", " 250.5 ");
  values.set("--samples-per-capture", "40");
  values.set("--signals", " Fz, Cz ,,Oz ");
  values.set_switch("--wide", true);
  EXPECT_EQ(values.number("--rate"), 250.5);
  EXPECT_EQ(values.count("--samples-per-capture"), 40);
  EXPECT_EQ(values.list("--signals"), (std::vector<std::string>{"Fz", "Cz", "Oz"}));
  EXPECT_TRUE(values.on("--wide"));
  EXPECT_FALSE(values.number("--annotation-seconds").has_value());
  values.set_switch("--wide", false);
  EXPECT_FALSE(values.has("--wide"));

  for (const char* bad : {"0", "-2", "nan", "inf", "12x", ""}) {
    values.set("--rate", bad);
    EXPECT_THROW(values.number("--rate"), Error) << bad;
  }
  values.set("--samples-per-capture", "2.5");
  try {
    values.count("--samples-per-capture");
    FAIL();
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "--samples-per-capture: \"2.5\" is not a whole number");
  }
}

TEST(ImportValues, AreCheckedAgainstTheFormatThatReadsTheFile) {
  const RecordingImporter& csv = importer_named("CSV");
  ImportValues values;
  values.set("--rate", "100");
  EXPECT_NO_THROW(check_import_values(csv, values));
  // Another format's flag, with the format's own reason when it has one.
  values.set("--dataset", "x");
  EXPECT_THROW(check_import_values(csv, values), Error);
  values.erase("--dataset");
  values.set("--stream", "x");
  try {
    check_import_values(csv, values);
    FAIL();
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("--stream: is not an option of CSV files", 0), 0u)
        << error.what();
  }
  values.erase("--stream");
  // An option only with a switch, and one never with it.
  values.set("--samples-per-capture", "4");
  EXPECT_THROW(check_import_values(csv, values), Error);
  values.set_switch("--wide", true);
  EXPECT_NO_THROW(check_import_values(csv, values));
  values.set("--class-column", "gesture");
  try {
    check_import_values(csv, values);
    FAIL();
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "--class-column: not with --wide");
  }
  const RecordingImporter& edf = importer_named("EDF+/BDF+");
  ImportValues rate;
  rate.set("--rate", "100");
  try {
    check_import_values(edf, rate);
    FAIL();
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "--rate: an EDF or BDF file states its own rate; leave --rate out");
  }
}

TEST(Importers, GiveTheCommandLineEachFlagOnceWithTheFormatsThatTakeIt) {
  const std::vector<SharedImportOption> shared = all_import_options();
  std::vector<std::string> flags;
  for (const SharedImportOption& option : shared) flags.push_back(option.option.flag);
  std::vector<std::string> sorted = flags;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
  const auto rate = std::find_if(shared.begin(), shared.end(), [](const SharedImportOption& o) {
    return o.option.flag == "--rate";
  });
  ASSERT_NE(rate, shared.end());
  EXPECT_EQ(rate->formats, (std::vector<std::string>{"CSV", "NumPy", "JSON", "HDF5", "MATLAB"}));
  for (const char* flag : {"--signals", "--stream", "--wide", "--captures", "--rate-variable"})
    EXPECT_NE(std::find(flags.begin(), flags.end(), flag), flags.end()) << flag;
}

TEST(Importers, FindAFileByItsExtensionElseByItsFirstBytes) {
  EXPECT_EQ(importer_for("a/b/Session.CSV")->name(), "CSV");
  EXPECT_EQ(importer_for("x.hdf5")->name(), "HDF5");
  EXPECT_EQ(importer_for("x.bdf")->name(), "EDF+/BDF+");
  EXPECT_EQ(importer_for("missing.unknown"), nullptr);
  // Real files of each kind under a name no importer claims.
  const test::TempFolder folder("tactile-importer-sniff");
  const std::string data = test::test_data_dir();
  const std::vector<std::pair<std::string, std::string>> files = {
      {data + "/interop/glove_session.xdf", "XDF"},
      {data + "/import/frames.npy", "NumPy"},
      {data + "/import/foreign.h5", "HDF5"}};
  for (const auto& [path, format] : files) {
    const std::string renamed = folder.file(std::filesystem::path(path).stem().string() + ".bin");
    std::filesystem::copy_file(path, renamed);
    const RecordingImporter* importer = importer_for(renamed);
    ASSERT_NE(importer, nullptr) << path;
    EXPECT_EQ(importer->name(), format);
  }
  EXPECT_NE(import_formats_text().find("MATLAB (.mat)"), std::string::npos);
  const std::vector<std::string> extensions = import_extensions();
  EXPECT_NE(std::find(extensions.begin(), extensions.end(), ".xdf"), extensions.end());
}

}  // namespace
}  // namespace tactile
