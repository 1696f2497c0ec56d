// The LabelStore's CSV and JSON exports. Both go through a temporary file that
// is renamed into place, so a failed export never leaves a partial file.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string_view>

#include "label_rows.h"
#include "tactile/error.h"
#include "tactile/io/label_store.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// A file written beside its final path and renamed over it by commit(); the
// temporary is removed if commit() is never reached.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path) : path_(std::move(path)) {
    // O_EXCL with a per-process name: two exports to one path never share a
    // temporary. 0666 lets the umask decide, as for any new file.
    for (int attempt = 0; attempt < 100 && file_ == nullptr; ++attempt) {
      temporary_ = path_ + ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(attempt);
      const int descriptor =
          open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (descriptor < 0) {
        if (errno == EEXIST) continue;
        fail("cannot create the output file");
      }
      file_ = fdopen(descriptor, "wb");
      if (file_ == nullptr) {
        const int error = errno;
        close(descriptor);
        unlink(temporary_.c_str());
        errno = error;
        fail("cannot create the output file");
      }
    }
    if (file_ == nullptr) throw Error(path_, "cannot create a temporary file beside it");
  }

  ~AtomicFile() {
    if (file_ != nullptr) fclose(file_);
    if (!committed_) unlink(temporary_.c_str());
  }

  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::string_view text) {
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) fail("cannot write");
  }

  void commit() {
    if (std::fflush(file_) != 0 || fsync(fileno(file_)) != 0) fail("cannot write");
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (closed != 0) fail("cannot write");
    if (std::rename(temporary_.c_str(), path_.c_str()) != 0) fail("cannot replace the output file");
    committed_ = true;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(path_, system_error(what)); }

  std::string path_, temporary_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

// RFC 4180: a field holding a comma, a quote or a line break is quoted, and
// its quotes doubled.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char character : text) {
    if (character == '"') quoted += '"';
    quoted += character;
  }
  return quoted + '"';
}

}  // namespace

void LabelStore::export_csv(const std::string& path, const LabelFilter& filter) const {
  const std::vector<Label> labels = list(filter);
  AtomicFile file(path);
  file.write(
      "id,recording,t0,t1,region,class,annotator,source,confidence,note,created,modified\r\n");
  for (const Label& label : labels) {
    std::string line = std::to_string(label.id);
    for (const std::string& field :
         {csv_field(label.recording), shortest_text(label.t0), shortest_text(label.t1),
          csv_field(label.region), csv_field(label.class_name), csv_field(label.annotator),
          std::string(to_string(label.source)), shortest_text(label.confidence),
          csv_field(label.note), csv_field(label.created), csv_field(label.modified)})
      line += "," + field;
    file.write(line + "\r\n");
  }
  file.commit();
}

std::string labels_json(const std::vector<Label>& labels) {
  nlohmann::json array = nlohmann::json::array();
  for (const Label& label : labels) array.push_back(label_rows::to_json(label));
  const nlohmann::json document{{"labels", std::move(array)}};
  return document.dump(2) + "\n";
}

void LabelStore::export_json(const std::string& path, const LabelFilter& filter) const {
  const std::string text = labels_json(list(filter));
  AtomicFile file(path);
  file.write(text);
  file.commit();
}

}  // namespace tactile
