// Dataset ARFF for Weka: every feature a numeric attribute, then the class as a nominal
// attribute listing the classes in first-seen order.
//
// Subject, recording, segment id and metadata are left out on purpose: Weka's classifiers
// use every attribute but the class, so a subject or recording attribute would let a
// model learn who touched rather than how. They are named in a comment in the header, and
// the CSV keeps them for protocols that split by them.
#include <algorithm>

#include "dataset_files.h"
#include "tactile/error.h"
#include "tactile/features/dataset.h"
#include "tactile/io/atomic_file.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// Weka reads bare words of letters, digits and . _ - (not starting with a digit or a
// sign, which its tokenizer might take for a number); anything else goes in single
// quotes with backslash escapes, as weka.core.Utils.quote writes it.
std::string arff_name(const std::string& name) {
  const auto bare_character = [](char character) {
    return (character >= 'a' && character <= 'z') || (character >= 'A' && character <= 'Z') ||
           (character >= '0' && character <= '9') || character == '_' || character == '.' ||
           character == '-';
  };
  const bool bare = !name.empty() && std::all_of(name.begin(), name.end(), bare_character) &&
                    !(name.front() >= '0' && name.front() <= '9') && name.front() != '-' &&
                    name.front() != '.';
  if (bare) return name;
  std::string quoted = "'";
  for (char character : name) {
    switch (character) {
      case '\'':
        quoted += "\\'";
        break;
      case '\\':
        quoted += "\\\\";
        break;
      case '\n':
        quoted += "\\n";
        break;
      case '\r':
        quoted += "\\r";
        break;
      case '\t':
        quoted += "\\t";
        break;
      default:
        quoted += character;
    }
  }
  return quoted + "'";
}

}  // namespace

void write_dataset_arff(const std::string& path, const Dataset& dataset,
                        const std::string& relation) {
  dataset_files::check_dataset(path, dataset);
  const std::vector<std::string> classes = dataset.class_names();
  std::string text =
      "% Written by tactile. One row per labelled segment; subject, recording,\n"
      "% segment_id and metadata are in the CSV export, left out here so that\n"
      "% no classifier learns them.\n";
  text += "@relation " + arff_name(relation.empty() ? std::string("tactile") : relation) + "\n\n";
  for (const FeatureColumn& column : dataset.columns) {
    // The description is kept as a comment: ARFF has no field for it.
    if (!column.description.empty()) {
      std::string description = column.description;
      std::replace(description.begin(), description.end(), '\n', ' ');
      text += "% " + description + "\n";
    }
    text += "@attribute " + arff_name(column.name) + " numeric\n";
  }
  text += "@attribute class {";
  for (size_t index = 0; index < classes.size(); ++index) {
    if (index > 0) text += ',';
    text += arff_name(classes[index]);
  }
  text += "}\n\n@data\n";
  for (int64_t row = 0; row < dataset.rows(); ++row) {
    for (int64_t column = 0; column < dataset.features.cols(); ++column)
      text += shortest_text(dataset.features(row, column)) + ",";
    text += arff_name(dataset.classes[row]) + "\n";
  }
  write_file_atomically(path, text);
}

}  // namespace tactile
