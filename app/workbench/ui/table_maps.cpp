#include "table_maps.h"

#include "jobs.h"
#include "results.h"
#include "tactile/error.h"
#include "tactile/ml/table_maps.h"
#include "tactile/skins/skin.h"
#include "views.h"

namespace tactile {

namespace {

// The ends of the derived views' jobs, applied on the window's thread (jobs.h).
void apply_som_fit(WorkbenchState& state, Job<SomState::Fit>& job) {
  AnalysisState& analysis = state.analysis;
  if (job.status() == JobStatus::kCancelled) analysis.som.held = true;
  std::optional<SomState::Fit> fit = job_result(state, job);
  if (!fit) return;
  analysis.som.model = std::move(fit->som);
  analysis.som.spread_for = nullptr;
  analysis.som.classes = std::move(fit->classes);
  analysis.som.winners = std::move(fit->winners);
  analysis.som.quality = fit->quality;
  analysis.som.table = analysis.results.dataset ? &*analysis.results.dataset : nullptr;
}

void apply_scatter_fit(WorkbenchState& state, Job<ScatterState::Fit>& job) {
  AnalysisState& analysis = state.analysis;
  if (job.status() == JobStatus::kCancelled) analysis.scatter.held = true;
  std::optional<ScatterState::Fit> fit = job_result(state, job);
  if (!fit) return;
  analysis.scatter.points = std::move(fit->points);
  analysis.scatter.explained = fit->explained;
}

void apply_map_made(WorkbenchState& state, Job<SomatosensoryState::Made>& job) {
  AnalysisState& analysis = state.analysis;
  std::optional<SomatosensoryState::Made> made = job_result(state, job);
  if (made && made->key == analysis.somatosensory.key) {
    analysis.somatosensory.map = std::move(made->map);
    analysis.somatosensory.agreement = made->agreement;
    analysis.somatosensory.layout.reset();
  }
}

// A job's map, with how far it keeps the body, measured on the worker too.
SomatosensoryState::Made made_map(const std::string& key, SomatosensoryMap map,
                                  const SkinLayout& layout) {
  SomatosensoryState::Made made{key, std::move(map), std::nullopt};
  try {
    made.agreement = map_body_agreement(made.map, layout);
  } catch (const Error&) {
    // Too few taxels to count neighbours: no figure.
  }
  return made;
}

}  // namespace

bool ensure_som(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  // The rows' winners are for this table (none without a table).
  const void* table = analysis.results.dataset ? &*analysis.results.dataset : nullptr;
  poll_jobs(state);
  if (analysis.som.model && analysis.som.table == table) return true;
  if (find_job(state, "som")) return false;  // fitting: the view shows its progress
  if (!analysis.som.model && analysis.som.held)
    return false;  // cancelled: the view offers it again
  try {
    if (!analysis.som.model) {
      if (!analysis.results.dataset) return false;
      // The map of the table: the flux paper's 7 x 7 SOM fitted on every row, on a worker
      // (18-20 s on a 454 x 1692 table), with its rows' winners.
      start_job<SomState::Fit>(
          state, "som", "SOM map",
          [table = analysis.results.dataset](JobProgress& progress) {
            ml::TableSom fit = ml::som_of(*table, [&progress](double fraction) {
              progress.report(fraction, "fitting the map");
              progress.check();
            });
            return SomState::Fit{std::move(fit.som), std::move(fit.classes), std::move(fit.winners),
                                 fit.quality};
          },
          apply_som_fit);
      return false;
    }
    // A loaded map: the winners of this table's rows (a pass over the rows, no fit).
    analysis.som.winners =
        analysis.results.dataset
            ? ml::som_winners(*analysis.som.model, analysis.results.dataset->features)
            : std::vector<int>{};
    analysis.som.table = table;
  } catch (const std::exception& error) {
    analysis.som.model.reset();
    analysis.som.quality.reset();
    analysis.som.spread_for = nullptr;
    return fail(state, std::string("SOM map: ") + error.what());
  }
  return true;
}

bool ensure_scatter(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  if (!analysis.results.dataset) return false;
  poll_jobs(state);
  if (find_job(state, "scatter")) return false;  // computing: the view shows its progress
  if (analysis.scatter.held) return false;       // cancelled: the view offers it again
  if (analysis.scatter.table == &*analysis.results.dataset)
    return analysis.scatter.points.rows() > 0;
  analysis.scatter.table = &*analysis.results.dataset;
  analysis.scatter.points.resize(0, 2);
  // The table on its first two principal components, on a worker (7.8 s at 454 x 1692).
  start_job<ScatterState::Fit>(
      state, "scatter", "scatter",
      [table = analysis.results.dataset](JobProgress& progress) {
        ml::TableScatter scatter =
            ml::scatter_of(table->features, progress.steps("principal components of " +
                                                           std::to_string(table->rows()) + " x " +
                                                           std::to_string(table->features.cols())));
        return ScatterState::Fit{std::move(scatter.points), scatter.explained};
      },
      apply_scatter_fit);
  return false;
}

bool ensure_somatosensory(WorkbenchState& state) {
  if (!state.document) return false;
  AnalysisState& analysis = state.analysis;
  const SkinLayout& layout = state.document->layout;
  const std::string modality =
      layout.modalities.empty() ? "" : layout.modalities[static_cast<size_t>(state.modality)];
  const std::string key =
      (analysis.somatosensory.corpus ? "corpus:" + state.workspace + ":" + layout.id
                                     : state.document->path) +
      "#" + modality;
  if (analysis.somatosensory.key == key) return analysis.somatosensory.map.has_value();
  analysis.somatosensory.key = key;
  analysis.somatosensory.map.reset();
  analysis.somatosensory.agreement.reset();
  analysis.somatosensory.layout.reset();
  // On a worker, cache and all (8.3 s for 30 min of Robovie's 274 channels the first time); a
  // map asked for meanwhile (another modality, the corpus) replaces it.
  if (analysis.somatosensory.corpus) {
    std::vector<std::string> files;
    for (const std::string& file : state.workspace_files)
      if (!state.damaged.count(file)) files.push_back(file);
    start_job<SomatosensoryState::Made>(
        state, "somatosensory", "somatosensory map (all recordings)",
        [key, files, layout, modality, index = state.modality,
         cache = somatosensory_corpus_cache_path(state.workspace, layout.id, modality)](
            JobProgress& progress) {
          // Every recording of this skin in the workspace (the others are left out).
          std::vector<std::string> same_skin;
          for (const std::string& file : files) {
            progress.check();
            try {
              if (RecordingFile(file).layout_id() == layout.id) same_skin.push_back(file);
            } catch (const Error&) {
            }
          }
          if (std::optional<SomatosensoryMap> cached =
                  read_somatosensory_corpus_cache(cache, same_skin))
            return made_map(key, std::move(*cached), layout);
          SomatosensoryMap map = somatosensory_corpus_map(
              same_skin, layout, index,
              progress.steps("correlations over " + std::to_string(same_skin.size()) +
                             " recordings"));
          write_somatosensory_corpus_cache(cache, same_skin, map);
          return made_map(key, std::move(map), layout);
        },
        apply_map_made);
  } else if (!dynamic_cast<const FileSampleSource*>(&state.document->samples())) {
    // A live stream: over what has arrived so far, copied now; no cache (nothing on disk yet).
    start_job<SomatosensoryState::Made>(
        state, "somatosensory", "somatosensory map",
        [key, read = recording_for_job(*state.document, 0.0, 0.0), layout,
         index = state.modality](JobProgress& progress) {
          const Recording recording = read(progress);
          return made_map(
              key,
              somatosensory_map(MemorySampleSource(recording, recording.streams.front()), layout,
                                index, progress.steps("correlations of the taxels")),
              layout);
        },
        apply_map_made);
  } else {
    start_job<SomatosensoryState::Made>(
        state, "somatosensory", "somatosensory map",
        [key, path = state.document->path, stream = state.document->samples().info().stream, layout,
         modality, index = state.modality](JobProgress& progress) {
          if (std::optional<SomatosensoryMap> cached = read_somatosensory_cache(path, modality))
            return made_map(key, std::move(*cached), layout);
          FileSourceOptions options;
          options.stream = stream;
          options.cache_bytes = int64_t{8} << 20;
          options.damaged_chunks_as_gaps = true;
          progress.report(0.0, "opening the recording");
          const FileSampleSource source(path, options);
          SomatosensoryMap map = somatosensory_map(source, layout, index,
                                                   progress.steps("correlations of the taxels"));
          write_somatosensory_cache(path, map);
          return made_map(key, std::move(map), layout);
        },
        apply_map_made);
  }
  return false;
}

}  // namespace tactile
