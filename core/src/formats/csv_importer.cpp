// CSV: long (a header, a time column, one column per channel; a class column and grouping
// columns) or wide (one capture per row, with a labels file) (formats/csv_files.h).
#include "builtin.h"
#include "tactile/error.h"

namespace tactile::formats {

namespace {

class CsvImporter : public RecordingImporter {
 public:
  std::string name() const override { return "CSV"; }
  std::vector<std::string> extensions() const override { return {".csv", ".txt"}; }
  std::vector<ImportOption> options() const override {
    using Kind = ImportOption::Kind;
    return {
        {"--rate", Kind::kNumber,
         "Sampling rate in Hz (long CSV: from the time column when left out)",
         "Hz (default for long CSV: from the time column)", "", ""},
        {"--wide", Kind::kSwitch, "One capture per row, channel-major, with a labels file",
         "one capture per row, with a labels file", "", ""},
        {"--samples-per-capture", Kind::kCount, "Samples of each channel in one capture (--wide)",
         "N", "--wide", ""},
        {"--labels-file", Kind::kFile, "One class per capture, by name or 0-based index (--wide)",
         "one class per capture", "--wide", ""},
        {"--class-names", Kind::kList,
         "Class names, comma-separated (--wide; default: the layout's)",
         "a,b,c (default: the layout's)", "--wide", ""},
        {"--class-column", Kind::kText,
         "Long CSV: the column of class names per row (none/empty: no touch)",
         "the column of class names", "", "--wide"},
        {"--group-columns", Kind::kList,
         "Long CSV: columns whose values split the table into recordings (e.g. "
         "subject,capture); --out is then a folder",
         "e.g. subject,capture: one recording per group", "", "--wide"},
    };
  }
  std::string refusal_of(const std::string& flag) const override {
    if (flag == "--dataset" || flag == "--key" || flag == "--class-array" || flag == "--captures")
      return "is for array files, not CSV";
    return {};
  }
  bool writes_several(const ImportValues& values) const override {
    return !values.list("--group-columns").empty();
  }

  ImportRead read(const std::string& path, const SkinLayout& layout,
                  const ImportValues& values) const override {
    ImportRead read;
    if (values.on("--wide")) {
      if (!values.has("--samples-per-capture"))
        throw Error("--samples-per-capture", "required with --wide");
      if (!values.has("--labels-file")) throw Error("--labels-file", "required with --wide");
      if (!values.has("--rate")) throw Error("--rate", "required with --wide");
      CsvWideOptions wide;
      wide.samples_per_capture = *values.count("--samples-per-capture");
      wide.labels_path = values.text("--labels-file");
      wide.class_names = values.list("--class-names");
      wide.rate_hz = *values.number("--rate");
      read.recordings.push_back(import_csv_wide(path, layout, wide));
      read.described = "wide CSV";
      return read;
    }
    CsvTableOptions table;
    table.rate_hz = values.number("--rate");
    table.class_column = values.text("--class-column");
    table.group_columns = values.list("--group-columns");
    if (!table.class_column.empty() || !table.group_columns.empty()) {
      read.recordings = import_csv_table(path, layout, table);
      read.described = "long CSV table";
      return read;
    }
    ImportedRecording imported;
    imported.recording = import_csv_long(path, layout, table);
    read.recordings.push_back(std::move(imported));
    read.described = "long CSV";
    return read;
  }
};

}  // namespace

std::unique_ptr<RecordingImporter> csv_importer() { return std::make_unique<CsvImporter>(); }

}  // namespace tactile::formats
