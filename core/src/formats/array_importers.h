#pragma once
// What the array formats (NumPy, JSON, HDF5, MATLAB) share: the options of an array's time and
// classes, and an array made into a recording of the layout.

#include <optional>
#include <string>
#include <vector>

#include "tactile/formats/array_files.h"
#include "tactile/formats/importer.h"

namespace tactile::formats {

// How an array format names the classes of its frames.
struct ArrayClasses {
  std::string help;     // what --class-array names ("a JSON key")
  std::string hint;     // the dialog's hint for it ("the key of the classes")
  std::string instead;  // where the classes are named, said when CSV's --class-column is given
};

// An array format (NumPy, JSON, HDF5, MATLAB): the options only it takes, then --rate,
// --class-array and --captures; CSV's --class-column refused by saying where it names classes.
class ArrayImporter : public RecordingImporter {
 public:
  explicit ArrayImporter(ArrayClasses classes) : classes_(std::move(classes)) {}
  std::vector<ImportOption> options() const final;
  std::string refusal_of(const std::string& flag) const final;

 protected:
  // The options only this format takes, listed first.
  virtual std::vector<ImportOption> own_options() const = 0;

 private:
  ArrayClasses classes_;
};

// The file's extension in lower case, with the dot.
std::string lower_extension(const std::string& path);

// --rate, refused as missing: an array carries no time.
double required_rate(const ImportValues& values);

// The array (and its classes, when given: names, or indices into the layout's classes) as one
// recording named after the file. `where` names the array in errors ("file.npz:pressure").
ImportRead array_recording(const std::string& path, const SkinLayout& layout, double rate_hz,
                           bool captures, const ImportedArray& array,
                           const std::optional<ImportedArray>& classes, const std::string& where,
                           const std::string& described);

}  // namespace tactile::formats
