#pragma once
// A label file format behind one interface, as recording formats are (formats/importer.h): ours
// (CSV and JSON, as `labels export` writes them) and other tools' (ELAN's .eaf, Label Studio's
// JSON; elan_and_label_studio.h). `tactile labels export`'s flags, the workbench's Export labels
// choices and the import of a label file come from this list; a program adds its own with
// register_label_format.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tactile/labels/elan_and_label_studio.h"
#include "tactile/labelstore/label.h"

namespace tactile {

class LabelFormat {
 public:
  virtual ~LabelFormat() = default;
  virtual std::string name() const = 0;         // "CSV", "JSON", "ELAN", "Label Studio"
  virtual std::string flag() const = 0;         // `labels export`'s flag: "--eaf"
  virtual std::string description() const = 0;  // one line: "ELAN .eaf (one tier per lane)"
  virtual std::string extension() const = 0;    // of the file an export writes: ".eaf"
  // True when a file holds one recording's labels (ELAN): an export of several is refused.
  virtual bool one_recording() const { return false; }
  // True when the format reads any file of its extension (our CSV and JSON): such a file may
  // as well be a recording's (`tactile import`), so it is not taken for a label file there.
  virtual bool reads_any_of_its_extension() const { return false; }
  // True when this format reads the file: by its lower-case extension and, where two formats
  // share one (.json), by the file's text, read only when asked for.
  virtual bool reads(const std::string& extension,
                     const std::function<const std::string&()>& text) const = 0;
  // The labels of the file, checked whole (`options`: the recording, and the tiers or
  // annotators mapped to lanes). Throws tactile::Error naming the file and the element. What
  // the file holds that is not a label and is not refused goes to `left_out`, one line per kind
  // ("2 choices from 'quality'").
  virtual std::vector<Label> read(const std::string& path, const InteropImport& options,
                                  std::vector<std::string>& left_out) const = 0;
  // The sources a user chooses among before an import (ELAN's tiers, Label Studio's
  // annotators); format "" when there is nothing to choose (our own files).
  virtual InteropSources sources(const std::string& path) const;
  // The labels as the file's text; `vocabulary` is the skin's classes (ELAN's controlled
  // vocabulary), `options` what other tools' formats take (Label Studio's project members).
  // Throws tactile::Error naming the option when the format cannot hold them.
  virtual std::string write(const std::vector<Label>& labels,
                            const std::vector<std::string>& vocabulary,
                            const InteropExport& options) const = 0;
};

// Adds a format, or replaces the one of the same name. Register at start-up.
void register_label_format(std::unique_ptr<LabelFormat> format);
// Every format, ours first.
std::vector<const LabelFormat*> label_formats();
// nullptr when none has this name.
const LabelFormat* label_format_named(const std::string& name);
// The format that reads the file; its text is read (refused past 256 MiB) only when a format
// asks for it. Throws tactile::Error naming the file and the formats when none reads it.
const LabelFormat& label_format_of(const std::string& path);

// The formats of other tools (label_eaf.cpp, label_studio.cpp).
std::unique_ptr<LabelFormat> elan_label_format();
std::unique_ptr<LabelFormat> label_studio_format();

}  // namespace tactile
