// The name -> runner table behind `tactile experiment NAME`, and the fixed-width text
// rendering of a report.
#include <algorithm>
#include <sstream>
#include <utility>

#include "tactile/error.h"
#include "tactile/experiments/experiment.h"
#include "tactile/experiments/flux.h"
#include "tactile/experiments/fur.h"
#include "tactile/experiments/kaboli.h"
#include "tactile/experiments/robovie.h"
#include "tactile/experiments/tsa.h"

namespace tactile::experiments {

namespace {

// In the order `experiment_names` lists them; each paper's engineer adds their lines here.
const std::vector<std::pair<std::string, ExperimentRunner>>& runner_table() {
  static const std::vector<std::pair<std::string, ExperimentRunner>> table = {
      {"kaboli-location", run_kaboli_location},
      {"kaboli-motion", run_kaboli_motion},
      {"kaboli-multitouch", run_kaboli_multitouch},
      {"kaboli-em", run_kaboli_em},
      {"kaboli-compare", run_kaboli_compare},
      {"tsa-classifiers", run_tsa_classifiers},
      {"fur-ml", run_fur_ml},
      {"robovie-clafic", run_robovie_clafic},
      {"flux-som", run_flux_som},
  };
  return table;
}

void append_rule(std::ostringstream& out, const std::vector<size_t>& widths) {
  for (size_t column = 0; column < widths.size(); ++column) {
    if (column > 0) out << "-+-";
    out << std::string(widths[column], '-');
  }
  out << "\n";
}

void append_row(std::ostringstream& out, const std::vector<std::string>& cells,
                const std::vector<size_t>& widths) {
  for (size_t column = 0; column < widths.size(); ++column) {
    if (column > 0) out << " | ";
    const std::string cell = column < cells.size() ? cells[column] : "";
    out << cell;
    // The last column is not padded so lines carry no trailing blanks.
    if (column + 1 < widths.size()) out << std::string(widths[column] - cell.size(), ' ');
  }
  out << "\n";
}

}  // namespace

std::vector<std::string> experiment_names() {
  std::vector<std::string> names;
  for (const auto& entry : runner_table()) names.push_back(entry.first);
  return names;
}

ExperimentReport run_experiment(const std::string& name, const ExperimentOptions& options) {
  for (const auto& entry : runner_table())
    if (entry.first == name) return entry.second(options);
  std::string known;
  for (const auto& entry : runner_table()) known += (known.empty() ? "" : ", ") + entry.first;
  throw Error(name, "unknown experiment; known experiments: " + (known.empty() ? "none" : known));
}

std::string format_report(const ExperimentReport& report) {
  std::ostringstream out;
  out << report.name;
  if (!report.paper.empty()) out << " (" << report.paper << ")";
  out << "\n";
  for (const ReportTable& table : report.tables) {
    out << "\n" << table.title << "\n";
    size_t columns = table.columns.size();
    for (const auto& row : table.rows) columns = std::max(columns, row.size());
    std::vector<size_t> widths(columns, 0);
    for (size_t column = 0; column < table.columns.size(); ++column)
      widths[column] = table.columns[column].size();
    for (const auto& row : table.rows)
      for (size_t column = 0; column < row.size(); ++column)
        widths[column] = std::max(widths[column], row[column].size());
    if (!table.columns.empty()) {
      append_row(out, table.columns, widths);
      append_rule(out, widths);
    }
    for (const auto& row : table.rows) append_row(out, row, widths);
    if (!table.note.empty()) out << table.note << "\n";
  }
  return out.str();
}

}  // namespace tactile::experiments
