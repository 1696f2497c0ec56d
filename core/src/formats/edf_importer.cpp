// EDF+ and BDF+: the signals chosen by label, the annotations as labels (formats/edf_files.h).
#include "array_importers.h"
#include "builtin.h"
#include "tactile/formats/edf_files.h"

namespace tactile::formats {

namespace {

class EdfImporter : public RecordingImporter {
 public:
  std::string name() const override { return "EDF+/BDF+"; }
  std::vector<std::string> extensions() const override { return {".edf", ".bdf"}; }
  bool recognises(const std::string& bytes) const override {
    return bytes.rfind("0       ", 0) == 0 || bytes.rfind(
                                                  "\xff"
                                                  "BIOSEMI",
                                                  0) == 0;
  }
  std::vector<ImportOption> options() const override {
    return {
        {"--signals", ImportOption::Kind::kList,
         "The signals by label, comma-separated, in channel order (default: every "
         "signal but the annotations)",
         "labels in channel order, e.g. Fz,Cz (default: every signal)", "", ""},
        {"--annotation-seconds", ImportOption::Kind::kNumber,
         "The length of annotations of zero or unknown duration (default: refused)",
         "length of annotations without one (default: refused)", "", ""},
    };
  }
  std::string refusal_of(const std::string& flag) const override {
    if (flag == "--rate") return "an EDF or BDF file states its own rate; leave --rate out";
    return "is not for EDF or BDF files (--signals chooses their signals)";
  }

  ImportRead read(const std::string& path, const SkinLayout& layout,
                  const ImportValues& values) const override {
    EdfImportOptions options;
    options.signals = values.list("--signals");
    options.annotation_seconds = values.number("--annotation-seconds");
    ImportRead read;
    read.recordings.push_back(import_edf(path, layout, options));
    read.described =
        (lower_extension(path) == ".bdf" ? ".bdf" : ".edf") + std::string(" recording");
    return read;
  }
};

}  // namespace

std::unique_ptr<RecordingImporter> edf_importer() { return std::make_unique<EdfImporter>(); }

}  // namespace tactile::formats
