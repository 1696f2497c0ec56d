// EDF+ and BDF+ recordings read with EDFlib (formats/edf_files.h): files written by EDFlib itself,
// read back value by value (within half a digital step), their annotations as labels, and the
// header checks that run before EDFlib sees a file.
#include <gtest/gtest.h>

#include <fstream>

#include "edf_test_files.h"
#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/formats/edf_files.h"
#include "tactile/formats/import.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {
namespace {

using testing::refusal_of;

using testing::edf_test_value;
using testing::EdfTestFile;

// Overwrites `text` at `offset` of the file, padded with spaces to `width`.
void patch(const std::string& path, size_t offset, const std::string& text, size_t width) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekp(static_cast<std::streamoff>(offset));
  std::string field = text;
  field.resize(width, ' ');
  file.write(field.data(), static_cast<std::streamsize>(field.size()));
}

class EdfImport : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::write_edf_test_file(edf_path, testing::edf_test_plus_file());
    testing::write_edf_test_file(bdf_path, testing::edf_test_bdf_file());
  }
  EdfImportOptions four_signals() const {
    EdfImportOptions options;
    options.signals = {"Fz", "Cz", "Pz", "Oz"};
    options.annotation_seconds = 0.5;
    return options;
  }
  // The samples of `signal` of `spec` in `column`: the physical values the file holds (written
  // as digital values), to the float the stream keeps.
  static void expect_values(const Stream& stream, int64_t column, const EdfTestFile& spec,
                            int signal) {
    const testing::EdfTestSignal& written = spec.signals[static_cast<size_t>(signal)];
    for (int64_t row = 0; row < stream.sample_count(); ++row) {
      const double expected = edf_test_value(written, signal, row);
      ASSERT_NEAR(stream.samples(row, column), expected, std::abs(expected) * 0x1p-23 + 1e-9)
          << "signal " << signal << " sample " << row;
    }
  }
  testing::TemporaryDirectory folder;
  std::string edf_path = folder.file("session.edf");
  std::string bdf_path = folder.file("press.bdf");
};

TEST_F(EdfImport, SignalsOfOneRateAreReadValueByValueWithTheirUnits) {
  const ImportedRecording imported = import_edf(edf_path, load_layout("strip:4"), four_signals());
  ASSERT_EQ(imported.recording.streams.size(), 1u);
  const Stream& stream = imported.recording.streams.front();
  EXPECT_EQ(stream.rate_hz, 100.0);
  ASSERT_EQ(stream.sample_count(), 300);
  ASSERT_EQ(stream.channel_count(), 4);
  const EdfTestFile spec = testing::edf_test_plus_file();
  for (int signal = 0; signal < 4; ++signal) expect_values(stream, signal, spec, signal);
  EXPECT_EQ(stream.units, (std::vector<std::string>{"uV", "uV", "uV", "uV"}));
  EXPECT_EQ(stream.channels,
            (std::vector<std::string>{
                load_layout("strip:4").channels[0].name, load_layout("strip:4").channels[1].name,
                load_layout("strip:4").channels[2].name, load_layout("strip:4").channels[3].name}));
  EXPECT_TRUE(stream.timestamps.empty());
  EXPECT_EQ(imported.recording.layout_id, "strip:4");
  EXPECT_EQ(imported.recording.id, "session");
}

TEST_F(EdfImport, TheHeaderFieldsBecomeMetadata) {
  const Metadata metadata =
      import_edf(edf_path, load_layout("strip:4"), four_signals()).recording.metadata;
  EXPECT_EQ(metadata.at("imported_from"), "session.edf");
  EXPECT_EQ(metadata.at("edf_format"), "EDF+");
  EXPECT_EQ(metadata.at("edf_signals"), "Fz,Cz,Pz,Oz");
  EXPECT_EQ(metadata.at("start_time"), "2024-03-05T14:07:09.25");
  EXPECT_EQ(metadata.at("patient_code"), "P-017");
  EXPECT_EQ(metadata.at("patient_name"), "Doe Jane");
  EXPECT_EQ(metadata.at("patient_sex"), "Female");
  EXPECT_EQ(metadata.at("patient_birthdate"), "21 jul 1990");
  EXPECT_EQ(metadata.at("technician"), "Lab tech");
  EXPECT_EQ(metadata.at("equipment"), "TouchRig 2");
  EXPECT_EQ(metadata.at("recording_additional"), "forearm session");
  EXPECT_EQ(metadata.count("patient"), 0u) << "EDF+ splits the patient field";

  EdfTestFile unknown = testing::edf_test_bdf_file();
  unknown.header_fields = false;  // EDFlib writes "X", EDF+'s unknown, in every subfield
  testing::write_edf_test_file(bdf_path, unknown);
  const Metadata bare = import_edf(bdf_path, load_layout("strip:2")).recording.metadata;
  EXPECT_EQ(bare.count("patient_name"), 0u);
  EXPECT_EQ(bare.count("patient_code"), 0u);
  EXPECT_EQ(bare.at("edf_format"), "BDF+");
}

TEST_F(EdfImport, AnnotationsBecomeGroundTruthLabelsOfTheirText) {
  const std::vector<Label> labels =
      import_edf(edf_path, load_layout("strip:4"), four_signals()).labels;
  ASSERT_EQ(labels.size(), 3u);
  const std::vector<std::tuple<double, double, std::string>> expected = {
      {0.5, 0.75, "Tap"}, {1.2, 2.0, "Stroke"}, {2.0, 2.5, "Pat"}};
  for (size_t k = 0; k < labels.size(); ++k) {
    EXPECT_NEAR(labels[k].t0, std::get<0>(expected[k]), 1e-9) << k;
    EXPECT_NEAR(labels[k].t1, std::get<1>(expected[k]), 1e-9) << k;
    EXPECT_EQ(labels[k].class_name, std::get<2>(expected[k])) << k << ": trimmed";
    EXPECT_EQ(labels[k].region, "all");
    EXPECT_EQ(labels[k].source, LabelSource::kGroundTruth);
    EXPECT_EQ(labels[k].annotator, "import");
  }
}

TEST_F(EdfImport, AnnotationsAtTheDatasEndAreDroppedAndReportedAndOnesRunningPastItClipped) {
  // EDFbrowser and clinical recorders close an EDF+ file with an annotation at its last
  // instant ("Recording ends" at 3 s of a 3-s file, here with the second EDFbrowser gives it).
  // EDFlib writes the structure they write: the TALs in the annotation signal of the records.
  // EDFlib's writer keeps room for one annotation per data record: records of half a second
  // (50 samples of the 100-Hz signals) hold these five.
  EdfTestFile spec = testing::edf_test_plus_file();
  for (size_t signal = 0; signal < 4; ++signal) spec.signals[signal].samples_per_record = 50;
  spec.records = 6;
  spec.record_seconds = 0.5;
  spec.annotations = {{0.5, 0.25, "Tap"},
                      {2.5, 1.0, "Movement"},        // runs 0.5 s past the end: clipped
                      {2.995, 0.5, "Artifact"},      // 5 ms left: less than a sample (10 ms)
                      {3.0, 1.0, "Recording ends"},  // at the end: no label
                      {3.5, 1.0, "After"}};          // after it: no label either
  testing::write_edf_test_file(edf_path, spec);
  const ImportedRecording imported = import_edf(edf_path, load_layout("strip:4"), four_signals());
  ASSERT_EQ(imported.recording.streams.front().sample_count(), 300);
  ASSERT_EQ(imported.labels.size(), 2u);
  EXPECT_EQ(imported.labels[0].class_name, "Tap");
  EXPECT_NEAR(imported.labels[0].t1, 0.75, 1e-9);
  EXPECT_EQ(imported.labels[1].class_name, "Movement");
  EXPECT_NEAR(imported.labels[1].t0, 2.5, 1e-9);
  EXPECT_EQ(imported.labels[1].t1, 3.0) << "clipped to the data, not 3.5";
  EXPECT_EQ(imported.recording.metadata.at("dropped_labels"),
            "annotation 3 at 2.995 s \"Artifact\": starts 0.004999999999999893 s before the "
            "data's end (3 s), less than one sample (0.01 s); annotation 4 at 3 s \"Recording "
            "ends\": at or after the data's end (3 s); annotation 5 at 3.5 s \"After\": at or "
            "after the data's end (3 s)");
  // A file whose annotations all lie inside says nothing.
  testing::write_edf_test_file(edf_path, testing::edf_test_plus_file());
  EXPECT_EQ(import_edf(edf_path, load_layout("strip:4"), four_signals())
                .recording.metadata.count("dropped_labels"),
            0u);
}

TEST_F(EdfImport, AnAnnotationAtTheEndNeedsNoLengthItIsNoLabel) {
  // "Recording ends" without a duration, as many recorders write it: no --annotation-seconds.
  EdfTestFile spec = testing::edf_test_plus_file();
  spec.annotations = {{0.5, 0.25, "Tap"}, {3.0, -1.0, "Recording ends"}};
  testing::write_edf_test_file(edf_path, spec);
  EdfImportOptions options = four_signals();
  options.annotation_seconds.reset();
  const ImportedRecording imported = import_edf(edf_path, load_layout("strip:4"), options);
  ASSERT_EQ(imported.labels.size(), 1u);
  EXPECT_NE(imported.recording.metadata.at("dropped_labels").find("\"Recording ends\""),
            std::string::npos);
}

TEST_F(EdfImport, AnAnnotationWithoutDurationIsRefusedWithItsOnsetAndText) {
  EdfImportOptions options = four_signals();
  options.annotation_seconds.reset();
  const std::string refusal =
      refusal_of([&] { import_edf(edf_path, load_layout("strip:4"), options); });
  EXPECT_NE(refusal.find("annotation 3 at 2 s \"Pat\""), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("--annotation-seconds"), std::string::npos) << refusal;
  options.annotation_seconds = 0.0;
  EXPECT_NE(refusal_of([&] {
              import_edf(edf_path, load_layout("strip:4"), options);
            }).find("--annotation-seconds"),
            std::string::npos);
}

TEST_F(EdfImport, SignalsOfDifferentRatesAreRefusedNamingEachRate) {
  EdfImportOptions options;
  options.annotation_seconds = 0.5;
  const std::string refusal =
      refusal_of([&] { import_edf(edf_path, load_layout("strip:5"), options); });
  EXPECT_NE(refusal.find("\"Fz\" 100 Hz"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("\"Resp\" 25 Hz"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("--signals"), std::string::npos) << refusal;
}

TEST_F(EdfImport, SignalsAreChosenByTheirTrimmedLabelInTheGivenOrder) {
  EdfImportOptions options;
  options.signals = {"Oz", " Fz "};
  options.annotation_seconds = 0.5;
  const ImportedRecording imported = import_edf(edf_path, load_layout("strip:2"), options);
  const Stream& stream = imported.recording.streams.front();
  const EdfTestFile spec = testing::edf_test_plus_file();
  expect_values(stream, 0, spec, 3);
  expect_values(stream, 1, spec, 0);
  EXPECT_EQ(imported.recording.metadata.at("edf_signals"), "Oz,Fz");

  options.signals = {"Resp"};
  const Stream resp =
      import_edf(edf_path, load_layout("strip:1"), options).recording.streams.front();
  EXPECT_EQ(resp.rate_hz, 25.0);
  EXPECT_EQ(resp.sample_count(), 75);
  EXPECT_EQ(resp.units.front(), "mV");
  expect_values(resp, 0, spec, 4);
}

TEST_F(EdfImport, AWrongSignalChoiceIsRefusedNamingTheFilesSignals) {
  EdfImportOptions options;
  options.annotation_seconds = 0.5;
  options.signals = {"Fz", "T3"};
  std::string refusal = refusal_of([&] { import_edf(edf_path, load_layout("strip:2"), options); });
  EXPECT_NE(refusal.find("--signals: no signal \"T3\""), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("Fz, Cz, Pz, Oz, Resp"), std::string::npos) << refusal;
  options.signals = {"EDF Annotations"};
  refusal = refusal_of([&] { import_edf(edf_path, load_layout("strip:1"), options); });
  EXPECT_NE(refusal.find("annotation signal"), std::string::npos) << refusal;
  options.signals = {"Fz", "Fz"};
  refusal = refusal_of([&] { import_edf(edf_path, load_layout("strip:2"), options); });
  EXPECT_NE(refusal.find("named twice"), std::string::npos) << refusal;
}

TEST_F(EdfImport, TheSignalCountMustBeTheLayoutsChannelCount) {
  const std::string refusal =
      refusal_of([&] { import_edf(edf_path, load_layout("strip:3"), four_signals()); });
  EXPECT_NE(refusal.find("4 signals (Fz, Cz, Pz, Oz) do not fit strip:3's 3 channels"),
            std::string::npos)
      << refusal;
}

TEST_F(EdfImport, BdfPlusHolds24BitValues) {
  const ImportedRecording imported = import_edf(bdf_path, load_layout("strip:2"));
  const Stream& stream = imported.recording.streams.front();
  EXPECT_EQ(stream.rate_hz, 64.0) << "32 samples per record of half a second";
  ASSERT_EQ(stream.sample_count(), 128);
  const EdfTestFile spec = testing::edf_test_bdf_file();
  // 24 bits: a step of 100 N / 2^24, 6e-6 N, finer than EDF's 16 bits could hold.
  EXPECT_NE(edf_test_value(spec.signals[0], 0, 1) - edf_test_value(spec.signals[0], 0, 0), 0.0);
  EXPECT_LT((spec.signals[0].physical_max - spec.signals[0].physical_min) / 16777215.0, 1e-5);
  expect_values(stream, 0, spec, 0);
  expect_values(stream, 1, spec, 1);
  EXPECT_EQ(imported.recording.metadata.at("edf_format"), "BDF+");
  EXPECT_EQ(stream.units, (std::vector<std::string>{"N", "N"}));
  ASSERT_EQ(imported.labels.size(), 2u);
  EXPECT_EQ(imported.labels[1].class_name, "Slide");
  EXPECT_NEAR(imported.labels[1].t0, 1.0, 1e-9);
  EXPECT_NEAR(imported.labels[1].t1, 1.5, 1e-9);
}

TEST_F(EdfImport, AFileShorterThanItsRecordsIsRefusedBeforeEdflibReadsIt) {
  const auto size = std::filesystem::file_size(edf_path);
  std::filesystem::resize_file(edf_path, size - 10);
  const std::string refusal =
      refusal_of([&] { import_edf(edf_path, load_layout("strip:4"), four_signals()); });
  EXPECT_NE(refusal.find("byte 236: 3 data records of"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("the file holds " + std::to_string(size - 10) + " bytes"),
            std::string::npos)
      << refusal;
}

TEST_F(EdfImport, HeadersThatLieAreRefusedWithTheirByteOffset) {
  const auto refused = [&](size_t offset, const std::string& text, size_t width) {
    testing::write_edf_test_file(edf_path, testing::edf_test_plus_file());
    patch(edf_path, offset, text, width);
    return refusal_of([&] { import_edf(edf_path, load_layout("strip:4"), four_signals()); });
  };
  EXPECT_NE(refused(236, "999999999", 8).find("byte 236: 99999999 data records"),
            std::string::npos);
  EXPECT_NE(refused(236, "-1", 8).find("unknown"), std::string::npos);
  EXPECT_NE(refused(252, "9999", 4).find("byte 252: number of signals \"9999\""),
            std::string::npos);
  EXPECT_NE(refused(252, "700", 4).find("expected 1 to 640"), std::string::npos);
  // A damaged signal count (bytes that are no text, a NUL among them) is quoted printable,
  // whole: the NUL neither cuts the message nor reaches the terminal.
  const std::string damaged = refused(252, std::string("\xfe\xff\x00\x18", 4), 4);
  EXPECT_NE(damaged.find("byte 252: number of signals \"\\xFE\\xFF\\x00\\x18\", expected 1 to 640"),
            std::string::npos)
      << damaged;
  EXPECT_EQ(damaged.find('\0'), std::string::npos);
  EXPECT_NE(refused(236,
                    std::string("1\0"
                                "1",
                                3),
                    8)
                .find("data records \"1\\x001\""),
            std::string::npos);
  EXPECT_NE(refused(252, "40", 4).find("less than the 10496-byte header its 40 signals need"),
            std::string::npos);
  // Six signals (five and the annotations): signal 1's samples per record at 256 + 6 * 216.
  EXPECT_NE(refused(256 + 6 * 216, "99999999", 8).find("byte 1552"), std::string::npos);
  EXPECT_NE(refused(256 + 6 * 216, "x", 8).find("signal 1's samples per data record \"x\""),
            std::string::npos);
  EXPECT_NE(refused(0, "1", 8).find("byte 0: not an EDF or BDF file"), std::string::npos);
  EXPECT_NE(refused(192, "EDF+D", 44).find("EDF+D (discontinuous) is not read"), std::string::npos);
  testing::write_text(edf_path, "0       short");
  EXPECT_NE(refusal_of([&] {
              import_edf(edf_path, load_layout("strip:4"));
            }).find("less than the 256-byte header"),
            std::string::npos);
}

TEST_F(EdfImport, AnnotatorImportReplacesThatAnnotatorsLabelsAndLeavesTheGroundTruth) {
  FileImportOptions options;
  options.file = edf_path;
  options.layout = "strip:4";
  options.values.set("--signals", "Fz,Cz,Pz,Oz");
  options.values.set("--annotation-seconds", "0.5");
  options.out = folder.file("session.h5");
  options.labels = folder.file("labels.db");
  import_file(options);  // the ground truth
  options.annotator = "maria";
  import_file(options);
  const FileImportReport again = import_file(options);
  EXPECT_EQ(again.stored, 3u);
  LabelStore store(options.labels);
  LabelFilter truth;
  truth.source = LabelSource::kGroundTruth;
  EXPECT_EQ(store.list(truth).size(), 3u);
  LabelFilter maria;
  maria.annotator = "maria";
  const std::vector<Label> labels = store.list(maria);
  ASSERT_EQ(labels.size(), 3u) << "a second import replaces maria's labels, never doubles them";
  for (const Label& label : labels) {
    EXPECT_EQ(label.source, LabelSource::kManual);
    EXPECT_EQ(label.recording, "session");
  }
  // One command each: undo by "import" takes back the last import only.
  store.undo("import");
  EXPECT_EQ(store.list(maria).size(), 3u) << "the first annotator import's labels are back";
  EXPECT_EQ(store.list(truth).size(), 3u);
}

TEST_F(EdfImport, TheSharedImportReadsEdfAndRefusesOptionsOfOtherFormats) {
  FileImportOptions options;
  options.file = edf_path;
  options.layout = "strip:4";
  options.values.set("--signals", "Fz,Cz,Pz,Oz");
  options.values.set("--annotation-seconds", "0.5");
  const ImportPreview preview = preview_import(options, 3);
  ASSERT_EQ(preview.refusal, "");
  EXPECT_EQ(preview.format, ".edf recording");
  EXPECT_EQ(preview.samples, 300);
  EXPECT_EQ(preview.rate_hz, 100.0);
  EXPECT_EQ(preview.classes, (std::vector<std::string>{"Tap", "Stroke", "Pat"}));
  ASSERT_EQ(preview.frames.size(), 3u);
  EXPECT_NEAR(preview.frames[2][1], edf_test_value(testing::edf_test_plus_file().signals[1], 1, 2),
              1e-4);
  EXPECT_EQ(importer_for("a.BDF")->name(), "EDF+/BDF+");
  options.values.set("--rate", "100.0");
  EXPECT_NE(preview_import(options).refusal.find("--rate: an EDF or BDF file states its own rate"),
            std::string::npos);
  options.values.erase("--rate");
  options.values.set("--class-array", "y");
  EXPECT_NE(preview_import(options).refusal.find("--class-array: is not for EDF or BDF files"),
            std::string::npos);
  options.values.erase("--class-array");
  options.file = folder.file("x.csv");
  EXPECT_NE(
      preview_import(options).refusal.find("--annotation-seconds: is not an option of CSV files"),
      std::string::npos)
      << preview_import(options).refusal;
}

}  // namespace
}  // namespace tactile
