// MATLAB: a variable (or a struct's field) of a .mat file, v4 to v7.3 (formats/mat_files.h); the
// rate may be a scalar variable of the same file.
#include <algorithm>
#include <cmath>
#include <optional>

#include "array_importers.h"
#include "builtin.h"
#include "tactile/error.h"
#include "tactile/formats/mat_files.h"

namespace tactile::formats {

namespace {

class MatImporter : public ArrayImporter {
 public:
  MatImporter()
      : ArrayImporter({"a .mat variable (cell array of names, char matrix, numeric vector)",
                       "the array of the classes",
                       "--class-array (an array or dataset of the same file)"}) {}
  std::string name() const override { return "MATLAB"; }
  std::vector<std::string> extensions() const override { return {".mat"}; }
  bool recognises(const std::string& bytes) const override {
    return bytes.rfind("MATLAB 5.0 MAT-file", 0) == 0 || bytes.rfind("MATLAB 7.3 MAT-file", 0) == 0;
  }

  ImportRead read(const std::string& path, const SkinLayout& layout,
                  const ImportValues& values) const override {
    std::optional<double> rate_hz = values.number("--rate");
    const std::string rate_variable = values.text("--rate-variable");
    if (!rate_variable.empty()) {
      if (rate_hz) throw Error("--rate-variable", "or --rate, not both");
      const ImportedArray rate = read_mat_variable(path, rate_variable);
      if (rate.text || rate.values.size() != 1 || !std::isfinite(rate.values.front()) ||
          rate.values.front() <= 0.0)
        throw Error("--rate-variable",
                    path + ":" + rate_variable + " is not one positive number (the rate in Hz)");
      rate_hz = rate.values.front();
    }
    if (!rate_hz) rate_hz = required_rate(values);
    const std::string dataset = values.text("--dataset");
    const ImportedArray array =
        read_mat_variable(path, dataset.empty() ? only_array(path) : dataset);
    std::optional<ImportedArray> classes;
    if (!values.text("--class-array").empty())
      classes = read_mat_variable(path, values.text("--class-array"));
    return array_recording(path, layout, *rate_hz, values.on("--captures"), array, classes,
                           dataset.empty() ? path : path + ":" + dataset, ".mat array");
  }

 private:
  // Without a name: the one numeric variable (or struct field) of two or more dimensions longer
  // than 1, as a .npz of one array needs none.
  static std::string only_array(const std::string& path) {
    std::vector<std::string> candidates;
    std::string list;
    for (const MatVariable& variable : mat_variables(path)) {
      if (!list.empty()) list += ", ";
      list += mat_variable_line(variable);
      if (variable.numeric() && std::count_if(variable.dims.begin(), variable.dims.end(),
                                              [](int64_t extent) { return extent > 1; }) >= 2)
        candidates.push_back(variable.name);
    }
    if (candidates.size() != 1)
      throw Error("--dataset", path + " holds " + std::to_string(candidates.size()) +
                                   " numeric arrays of 2 or more dimensions: name one (" +
                                   (list.empty() ? "no variables" : list) + ")");
    return candidates.front();
  }

 protected:
  std::vector<ImportOption> own_options() const override {
    return {{"--dataset", ImportOption::Kind::kText,
             "The variable to read (s.field for a struct's field; default: the file's one "
             "array)",
             "the variable, s.field (default: the only array)", "", ""},
            {"--rate-variable", ImportOption::Kind::kText,
             "The scalar variable holding the rate in Hz (e.g. fs or s.rate; not with --rate)",
             "the variable holding the rate in Hz (not with --rate)", "", ""}};
  }
};

}  // namespace

std::unique_ptr<RecordingImporter> mat_importer() { return std::make_unique<MatImporter>(); }

}  // namespace tactile::formats
