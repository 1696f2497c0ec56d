// XDF (LabRecorder): a numeric stream resampled to its nominal rate, a markers stream's
// markers as labels (formats/xdf_files.h).
#include "builtin.h"
#include "tactile/formats/xdf_files.h"
#include "tactile/text.h"

namespace tactile::formats {

namespace {

class XdfImporter : public RecordingImporter {
 public:
  std::string name() const override { return "XDF"; }
  std::vector<std::string> extensions() const override { return {".xdf"}; }
  bool recognises(const std::string& bytes) const override { return bytes.rfind("XDF:", 0) == 0; }
  std::vector<ImportOption> options() const override {
    return {
        {"--stream", ImportOption::Kind::kText,
         "The data stream, NAME or type:TYPE (default: the only numeric stream with a "
         "nominal rate)",
         "NAME or type:TYPE (default: the only numeric stream with a rate)", "", ""},
        {"--markers", ImportOption::Kind::kText,
         "The markers stream whose markers become ground-truth labels, NAME or type:TYPE "
         "(default: the only markers stream)",
         "NAME or type:TYPE (default: the only markers stream)", "", ""},
    };
  }
  std::string refusal_of(const std::string& flag) const override {
    if (flag == "--rate") return "an XDF stream is resampled to its own nominal rate";
    return "is not for XDF files (--stream and --markers choose its streams)";
  }

  ImportRead read(const std::string& path, const SkinLayout& layout,
                  const ImportValues& values) const override {
    ImportRead read;
    read.recordings.push_back(import_xdf(
        path, layout, XdfImportOptions{values.text("--stream"), values.text("--markers")}));
    read.described =
        "XDF stream " + in_quotes(read.recordings.front().recording.metadata.at("xdf_stream"));
    return read;
  }
};

}  // namespace

std::unique_ptr<RecordingImporter> xdf_importer() { return std::make_unique<XdfImporter>(); }

}  // namespace tactile::formats
