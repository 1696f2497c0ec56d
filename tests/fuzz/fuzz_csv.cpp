// The CSV readers: long (with and without a time column), the long table with class and
// group columns, and wide captures with their labels file. The first byte picks the reader
// and its options; for wide captures the rest is split at the first NUL into the CSV and the
// labels file.
#include <algorithm>

#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/formats/csv_files.h"
#include "tactile/layout/skin_layout.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const SkinLayout grid = make_grid_layout(2, 2);
  static const SkinLayout strip = make_strip_layout(3);
  const uint8_t mode = data[0];
  const auto rest = fuzz::bytes_of(data + 1, size - 1);
  const SkinLayout& layout = mode & 0x08 ? strip : grid;
  try {
    switch (mode % 4) {
      case 0: {
        CsvLongOptions options;
        if (mode & 0x10) options.rate_hz = 100.0;
        if (mode & 0x20) options.has_time_column = (mode & 0x40) != 0;
        import_csv_long(fuzz::write_input(rest, ".csv"), layout, options);
        break;
      }
      case 1: {
        CsvTableOptions options;
        if (mode & 0x10) options.rate_hz = 50.0;
        if (mode & 0x20) options.class_column = "gesture";
        if (mode & 0x40) options.group_columns = {"subject"};
        if (mode & 0x80) options.group_columns.push_back("capture");
        import_csv_table(fuzz::write_input(rest, ".csv"), layout, options);
        break;
      }
      default: {
        const auto split = std::find(rest.begin(), rest.end(), uint8_t{0});
        const auto csv = rest.subspan(0, static_cast<size_t>(split - rest.begin()));
        const auto labels =
            split == rest.end() ? rest.subspan(rest.size()) : rest.subspan(csv.size() + 1);
        CsvWideOptions options;
        options.samples_per_capture = 1 + (mode >> 4);
        options.rate_hz = 10.0;
        options.labels_path = fuzz::write_input(labels, ".labels.txt");
        if (mode & 0x04) options.class_names = {"tap", "stroke"};
        import_csv_wide(fuzz::write_input(csv, ".csv"), layout, options);
        break;
      }
    }
  } catch (const Error&) {
  }
  return 0;
}
