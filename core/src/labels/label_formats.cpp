// The label formats (labels/label_format.h): the list, and our own two, CSV and JSON, as
// `labels export` writes them and labelstore/label_csv_json.h reads them. ELAN and Label Studio are
// rows of their own files (label_eaf.cpp, label_studio.cpp).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <mutex>

#include "tactile/error.h"
#include "tactile/labels/label_format.h"
#include "tactile/labelstore/label_csv_json.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/text.h"

namespace tactile {

namespace {

class OurCsvFormat : public LabelFormat {
 public:
  std::string name() const override { return "CSV"; }
  std::string flag() const override { return "--csv"; }
  std::string description() const override { return "CSV (RFC 4180)"; }
  std::string extension() const override { return ".csv"; }
  bool reads(const std::string& extension,
             const std::function<const std::string&()>&) const override {
    return extension == ".csv";
  }
  bool reads_any_of_its_extension() const override { return true; }
  std::vector<Label> read(const std::string& path, const InteropImport&,
                          std::vector<std::string>&) const override {
    return read_labels_csv(path);
  }
  std::string write(const std::vector<Label>& labels, const std::vector<std::string>&,
                    const InteropExport&) const override {
    return labels_csv(labels);
  }
};

class OurJsonFormat : public LabelFormat {
 public:
  std::string name() const override { return "JSON"; }
  std::string flag() const override { return "--json"; }
  std::string description() const override { return "JSON"; }
  std::string extension() const override { return ".json"; }
  bool reads(const std::string& extension,
             const std::function<const std::string&()>& text) const override {
    return extension == ".json" && !is_label_studio_json(text());
  }
  bool reads_any_of_its_extension() const override { return true; }
  std::vector<Label> read(const std::string& path, const InteropImport&,
                          std::vector<std::string>&) const override {
    return read_labels_json(path);
  }
  std::string write(const std::vector<Label>& labels, const std::vector<std::string>&,
                    const InteropExport&) const override {
    return labels_json(labels);
  }
};

struct Registry {
  std::mutex mutex;
  std::vector<std::unique_ptr<LabelFormat>> formats;
};

Registry& registry() {
  static Registry* instance = [] {
    auto* made = new Registry;  // never destroyed: formats outlive every static user
    made->formats.push_back(std::make_unique<OurCsvFormat>());
    made->formats.push_back(std::make_unique<OurJsonFormat>());
    made->formats.push_back(elan_label_format());
    made->formats.push_back(label_studio_format());
    return made;
  }();
  return *instance;
}

}  // namespace

InteropSources LabelFormat::sources(const std::string&) const { return {}; }

void register_label_format(std::unique_ptr<LabelFormat> format) {
  if (!format || format->name().empty()) throw Error("label format", "needs a name");
  Registry& list = registry();
  const std::lock_guard<std::mutex> lock(list.mutex);
  for (auto& existing : list.formats)
    if (existing->name() == format->name()) {
      existing = std::move(format);
      return;
    }
  list.formats.push_back(std::move(format));
}

std::vector<const LabelFormat*> label_formats() {
  Registry& list = registry();
  const std::lock_guard<std::mutex> lock(list.mutex);
  std::vector<const LabelFormat*> all;
  for (const auto& format : list.formats) all.push_back(format.get());
  return all;
}

const LabelFormat* label_format_named(const std::string& name) {
  for (const LabelFormat* format : label_formats())
    if (format->name() == name) return format;
  return nullptr;
}

const LabelFormat& label_format_of(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string contents;
  bool read = false;
  const std::function<const std::string&()> text = [&]() -> const std::string& {
    if (!read) contents = read_interop_text(path);
    read = true;
    return contents;
  };
  std::vector<std::string> known;
  for (const LabelFormat* format : label_formats()) {
    if (format->reads(extension, text)) return *format;
    known.push_back(format->name() + " (" + format->extension() + ")");
  }
  throw Error(path, "not a label file import reads: " + joined(known));
}

}  // namespace tactile
