#include "labelling.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <utility>

#include "jobs.h"
#include "tactile/error.h"
#include "tactile/labels/commands.h"
#include "tactile/labels/predict.h"
#include "tactile/labels/region.h"
#include "tactile/labels/suggestions.h"
#include "tactile/segment/fit.h"
#include "tactile/segment/presets.h"
#include "tactile/segment/segmenter.h"
#include "tactile/signal/taxel_values.h"
#include "tactile/text.h"
#include "video.h"
#include "views.h"

namespace tactile {

namespace {

// A mark at the cursor; while playing, where the operator meant it: the reaction
// time earlier.
double mark_time(const WorkbenchState& state) {
  double t = state.clock.time();
  if (state.clock.playing()) t -= state.labelling.reaction_seconds;
  return std::clamp(t, state.clock.start(), state.clock.end());
}

// After an edit: the lanes are rebuilt from the store, what was made is selected.
void after_edit(WorkbenchState& state, int64_t selected, const std::string& notice) {
  state.document->reload_labels();
  state.selection.labels.clear();
  if (selected != 0) state.selection.labels.push_back(selected);
  state.error.clear();
  state.notice = notice;
}

std::optional<Label> selected_label(const WorkbenchState& state) {
  if (!state.document || state.selection.labels.empty()) return std::nullopt;
  for (const Label& label : state.document->labels)
    if (label.id == state.selection.labels.front()) return label;
  return std::nullopt;
}

bool own(const WorkbenchState& state, const Label& label) {
  return label.source == LabelSource::kManual && label.annotator == state.labelling.annotator;
}

// The labels as the store has them now (after another writer's commit or a refused edit): the
// selection keeps the labels that still exist, the cursor and the marks stay.
void reload_keeping_selection(WorkbenchState& state) {
  Document& document = *state.document;
  document.reload_labels();
  std::erase_if(state.selection.labels, [&document](int64_t id) {
    return std::none_of(document.labels.begin(), document.labels.end(),
                        [id](const Label& label) { return label.id == id; });
  });
}

// The recording a journal row is about (its label before or after), "" when unreadable.
std::string journal_recording(const JournalEntry& entry) {
  for (const std::string* text : {&entry.after_json, &entry.before_json}) {
    if (text->empty()) continue;
    const nlohmann::json object = nlohmann::json::parse(*text, nullptr, false);
    if (object.is_object() && object.contains("recording") && object["recording"].is_string())
      return object["recording"].get<std::string>();
  }
  return {};
}

// "bob added 2 labels, changed 1; carla removed 1": the others' journal rows about this
// recording (the operator's own rows, from a job of this workbench, are not news).
std::string others_news(const std::vector<JournalEntry>& entries, const std::string& recording,
                        const std::string& operator_name) {
  static const std::map<std::string, std::string> kVerbs = {
      {"insert", "added"},    {"update", "changed"}, {"delete", "removed"},
      {"reject", "rejected"}, {"undo", "undid"},     {"redo", "redid"}};
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, int>>>> people;
  for (const JournalEntry& entry : entries) {
    if (entry.annotator == operator_name || journal_recording(entry) != recording) continue;
    const auto verb = kVerbs.find(entry.action);
    if (verb == kVerbs.end()) continue;
    auto person = std::find_if(people.begin(), people.end(),
                               [&](const auto& known) { return known.first == entry.annotator; });
    if (person == people.end()) person = people.insert(people.end(), {entry.annotator, {}});
    auto counted = std::find_if(person->second.begin(), person->second.end(),
                                [&](const auto& known) { return known.first == verb->second; });
    if (counted == person->second.end())
      person->second.push_back({verb->second, 1});
    else
      ++counted->second;
  }
  std::string news;
  for (const auto& [annotator, counts] : people) {
    news += (news.empty() ? "" : "; ") + annotator;
    for (size_t k = 0; k < counts.size(); ++k)
      news += (k == 0 ? " " : ", ") + counts[k].first + " " + std::to_string(counts[k].second) +
              (k == 0 ? (counts[k].second == 1 ? " label" : " labels") : "");
  }
  return news;
}

// A refused edit: nothing of it was written; the view shows the store as it is now.
bool refuse(WorkbenchState& state, const EditConflict& conflict) {
  reload_keeping_selection(state);
  return fail(state, conflict.message());
}

}  // namespace

void follow_other_writers(WorkbenchState& state) {
  if (!state.document) return;
  Document& document = *state.document;
  try {
    if (!document.store) {
      // Another writer may create the store beside the recording: look now and then.
      if (!document.labels_refused.empty() || document.path.empty() || state.frame % 30 != 0)
        return;
      const std::string beside =
          document.labels_path.empty()
              ? (std::filesystem::path(document.path).parent_path() / "labels.db").string()
              : document.labels_path;
      std::error_code missing;
      if (!std::filesystem::exists(beside, missing)) return;
      document.label_store();
      document.journal_seen = 0;  // everything in it is news
      document.store_changes = document.store->change_count() - 1;
    }
    const int64_t changes = document.store->change_count();
    if (changes == document.store_changes) return;
    document.store_changes = changes;
    const std::vector<JournalEntry> entries = document.store->journal_after(document.journal_seen);
    if (!entries.empty()) document.journal_seen = entries.back().sequence;
    reload_keeping_selection(state);
    const std::string news =
        others_news(entries, document.recording_id(), state.labelling.annotator);
    if (!news.empty()) state.notice = news;
  } catch (const Error& error) {
    fail(state, error.what());
  }
}

std::optional<std::vector<int64_t>> apply_command(WorkbenchState& state, const LabelEdit& edit) {
  try {
    std::vector<int64_t> ids = state.document->label_store().apply(edit, state.labelling.annotator);
    return ids;
  } catch (const EditConflict& conflict) {
    refuse(state, conflict);
    return std::nullopt;
  } catch (const Error& error) {
    fail(state, error.what());
    return std::nullopt;
  }
}

const LaneIndex* active_lane(const WorkbenchState& state) {
  if (!state.document) return nullptr;
  const int lane = state.document->lanes.find({LabelSource::kManual, state.labelling.annotator});
  return lane < 0 ? nullptr : &state.document->lanes.lanes[static_cast<size_t>(lane)];
}

bool mark_start(WorkbenchState& state) {
  if (!state.document) return false;
  state.labelling.mark_start = mark_time(state);
  if (state.labelling.mark_end && *state.labelling.mark_end <= *state.labelling.mark_start)
    state.labelling.mark_end.reset();
  return true;
}

bool mark_end(WorkbenchState& state) {
  if (!state.document) return false;
  const double t = mark_time(state);
  if (state.labelling.mark_start && t <= *state.labelling.mark_start)
    return fail(state, "the end mark must come after the start mark (" +
                           format_seconds(*state.labelling.mark_start) + ")");
  state.labelling.mark_end = t;
  return true;
}

bool choose_class(WorkbenchState& state, int key) {
  if (!state.document) return false;
  const std::vector<std::string>& classes = state.document->classes;
  if (key < 1 || key > static_cast<int>(classes.size()))
    return fail(state, "no class on key " + std::to_string(key) + " (the skin has " +
                           std::to_string(classes.size()) + ")");
  const std::string& chosen = classes[static_cast<size_t>(key - 1)];
  // A digit on a selected prediction (no marks set) corrects it at once.
  const std::optional<Label> selected = selected_label(state);
  if (selected && selected->source == LabelSource::kModel && !state.labelling.mark_start &&
      !state.labelling.mark_end)
    return confirm_prediction(state, chosen);
  state.labelling.pending_class = chosen;
  return true;
}

bool confirm_prediction(WorkbenchState& state, const std::string& corrected_class) {
  const std::optional<Label> selected = selected_label(state);
  if (!selected || selected->source != LabelSource::kModel)
    return fail(state, "select a prediction (a label of the model lane) first");
  const std::string class_name = corrected_class.empty() ? selected->class_name : corrected_class;
  if (class_name == kUnknownClass)
    return fail(state, "the model answered unknown: press its digit");
  if (!apply_command(state, adopt_edit(*selected, class_name, state.labelling.annotator)))
    return false;
  after_edit(state, 0,
             (class_name == selected->class_name ? "confirmed " : "corrected to ") + class_name +
                 " " + format_seconds(selected->t0));
  next_uncertain_prediction(state);
  return true;
}

bool next_uncertain_prediction(WorkbenchState& state) {
  if (!state.document) return false;
  const int lane_index = state.document->lanes.find({LabelSource::kModel, kModelAnnotator});
  if (lane_index < 0)
    return fail(state, "no predictions: run `tactile predict` or Model > Predict");
  const LaneIndex* own_lane = active_lane(state);
  const Label* best =
      least_sure_prediction(state.document->lanes.lanes[static_cast<size_t>(lane_index)].labels(),
                            own_lane ? own_lane->labels() : std::span<const Label>{});
  if (!best) {
    state.notice = "every prediction is decided";
    return false;
  }
  const double best_margin = prediction_margin(*best);
  state.selection.labels = {best->id};
  state.clock.seek(best->t0);
  const double span = std::max(1.0, 3.0 * (best->t1 - best->t0));
  state.plot.view_t0 = best->t0 - span / 3.0;
  state.plot.view_t1 = state.plot.view_t0 + span;
  state.notice = "least sure: " + best->class_name + " (margin " +
                 std::to_string(best_margin).substr(0, 5) + ") - digit corrects, Y confirms";
  return true;
}

bool commit_label(WorkbenchState& state) {
  if (!state.document) return false;
  LabellingState& labelling = state.labelling;
  Document& document = *state.document;
  try {
    if (labelling.mark_start && labelling.mark_end) {
      if (labelling.pending_class.empty())
        return fail(state, "choose the class with 1-9 before Enter");
      Label label;
      label.recording = document.recording_id();
      label.t0 = *labelling.mark_start;
      label.t1 = *labelling.mark_end;
      label.region = region_of_taxels(document.layout, state.selection.taxels);
      label.class_name = labelling.pending_class;
      label.annotator = labelling.annotator;
      label.source = LabelSource::kManual;
      const auto ids = apply_command(state, add_edit(label));
      if (!ids) return false;
      const int64_t id = ids->front();
      labelling.mark_start.reset();
      labelling.mark_end.reset();
      labelling.pending_class.clear();
      after_edit(state, id,
                 "labelled " + label.class_name + " " + format_seconds(label.t0) + " to " +
                     format_seconds(label.t1));
      return true;
    }
    // No marks: a class key then Enter changes the class of the selected own label.
    const std::optional<Label> selected = selected_label(state);
    if (selected && own(state, *selected) && !labelling.pending_class.empty()) {
      if (!apply_command(state, class_edit(*selected, labelling.pending_class))) return false;
      after_edit(state, selected->id,
                 "label " + std::to_string(selected->id) + " is now " + labelling.pending_class);
      labelling.pending_class.clear();
      return true;
    }
    return fail(state, "set the start and end with [ and ] first");
  } catch (const Error& error) {
    return fail(state, error.what());
  }
}

bool remove_selected_label(WorkbenchState& state) {
  const std::optional<Label> selected = selected_label(state);
  if (!selected) return fail(state, "no label selected");
  if (!own(state, *selected))
    return fail(state, "only labels of your own lane (" + state.labelling.annotator +
                           ") are removed with Delete");
  if (!apply_command(state, remove_edit(*selected))) return false;
  after_edit(state, 0, "removed label " + std::to_string(selected->id));
  return true;
}

namespace {

// "2026-11-28T17:20:59.123Z" as "2026-11-28 17:20:59 UTC".
std::string readable_time(std::string time) {
  if (time.size() >= 19 && time[10] == 'T')
    return time.substr(0, 10) + " " + time.substr(11, 8) + " UTC";
  return time;
}

// Brings [t0, t1] into the plot's view (keeping its width when it fits) and the cursor to t0.
void show_span(WorkbenchState& state, double t0, double t1) {
  if (t0 > t1) return;
  SignalPlotState& plot = state.plot;
  const double width = plot.view_t1 - plot.view_t0;
  if (t1 - t0 > 0.9 * width) {
    const double margin = 0.1 * std::max(0.2, t1 - t0);
    plot.view_t0 = t0 - margin;
    plot.view_t1 = t1 + margin;
  } else if (t0 < plot.view_t0 || t1 > plot.view_t1) {
    plot.view_t0 = 0.5 * (t0 + t1) - 0.5 * width;
    plot.view_t1 = plot.view_t0 + width;
  }
  plot.fitted = true;
  state.clock.seek(t0);
}

}  // namespace

bool undo_edit(WorkbenchState& state, bool redo) {
  if (!state.document) return false;
  // A video's offset edited after the newest label edit is taken back first (video.h).
  if (undo_video_edit(state, redo)) return true;
  state.video.redo_is_video = false;
  LabellingState& labelling = state.labelling;
  // While a segmenter run goes on, Ctrl+Z stops it: the newest thing the operator did is that
  // run, not the label before it.
  AnyJob* run = redo ? nullptr : running_job(state, "segmenter");
  if (run) {
    run->cancel();
    labelling.run_cancelled_by_undo = true;
    state.error.clear();
    state.notice = run->name() + " cancelled (Ctrl+Z): nothing of it is kept";
    return true;
  }
  EditSummary taken_back, changed;
  try {
    LabelStore& store = state.document->label_store();
    if (!redo) taken_back = summarize_edit(store.next_undo(labelling.annotator));
    const int64_t before = store.last_sequence();
    const bool done = redo ? store.redo(labelling.annotator) : store.undo(labelling.annotator);
    if (!done) return fail(state, redo ? "nothing to redo" : "nothing to undo");
    changed = summarize_edit(store.journal_after(before));
  } catch (const EditConflict& conflict) {
    return refuse(state, conflict);
  } catch (const Error& error) {
    return fail(state, error.what());
  }
  // Says what was taken back, and when it was made before this recording was opened (the last
  // session's segmenter run, say), so that a first Ctrl+Z takes nothing back unseen.
  std::string notice =
      redo ? "redone: " + describe_edit(changed) : "undone: " + describe_edit(taken_back);
  if (!redo && taken_back.first_sequence <= state.document->journal_at_open)
    notice += ", made in an earlier session (" + readable_time(taken_back.time) +
              "); Ctrl+Shift+Z redoes it";
  after_edit(state, 0, notice);
  show_span(state, changed.t0, changed.t1);
  return true;
}

namespace {

// Selects the suggestion of `method` starting after t (or the first), moving the cursor.
bool select_next_suggestion(WorkbenchState& state, const std::string& method, double after) {
  const int lane_index = state.document->lanes.find({LabelSource::kSegmenter, method});
  if (lane_index < 0) return false;
  const LaneIndex& lane = state.document->lanes.lanes[static_cast<size_t>(lane_index)];
  const int64_t next = lane.next_after(after);
  if (next < 0) return false;
  const Label& label = lane.labels()[static_cast<size_t>(next)];
  state.selection.labels = {label.id};
  state.clock.seek(label.t0);
  return true;
}

}  // namespace

namespace {

// The ends of the two labelling jobs, applied on the window's thread (jobs.h).
void apply_finished_segmenter(WorkbenchState& state, Job<LabellingState::SegmentsFound>& job);
void apply_finished_fit(WorkbenchState& state, Job<LabellingState::SegmenterFitted>& job);

}  // namespace

bool run_segmenter(WorkbenchState& state, const std::string& method) {
  if (!state.document) return false;
  Document& document = *state.document;
  state.labelling.last_segmenter = method;
  state.labelling.run_cancelled_by_undo = false;
  try {
    const Parameters parameters =
        Parameters::parse(state.labelling.segmenter_params.data(), "segmenter parameters");
    const std::string database = document.label_store().path();  // created on first need
    // On a worker, reading and storing included (2.9 s for 30 min of Robovie's 274 channels
    // when it ran in one frame). A second G replaces a run still going.
    start_job<LabellingState::SegmentsFound>(
        state, "segmenter", "segmenter " + method,
        [open = source_for_job(document), layout = document.layout, method, parameters,
         path = document.path, database, recording = document.recording_id(),
         annotator = state.labelling.annotator](JobProgress& progress) {
          // adaptive reads the file a channel at a time: 30 minutes of Robovie are never held
          // whole (they were 207 MB, and the method's copies twice that again).
          std::vector<Label> segments = segment_source(
              method, *open(), layout, parameters, progress.steps("finding segments", 0.0, 0.9));
          progress.check();
          progress.report(0.95, "storing the suggestions");
          LabelStore store(database, LabelStore::OpenMode::kExisting);
          const SegmenterRun run = segmenter_run(store, recording, method, std::move(segments));
          progress.check();  // the last place to stop: what follows is one transaction
          // One command of the operator's: Ctrl+Z takes back the whole run.
          store.apply(run.edit, annotator);
          return LabellingState::SegmentsFound{path, method, run.annotator, run.edit.add.size(),
                                               run.rejected};
        },
        apply_finished_segmenter);
    state.error.clear();
    state.notice = method + ": finding segments...";
    return true;
  } catch (const std::exception& error) {
    return fail(state, error.what());
  }
}

namespace {

void apply_finished_segmenter(WorkbenchState& state, Job<LabellingState::SegmentsFound>& job) {
  LabellingState& labelling = state.labelling;
  const bool by_undo = std::exchange(labelling.run_cancelled_by_undo, false);
  const std::string undo_notice = state.notice;
  std::optional<LabellingState::SegmentsFound> found = job_result(state, job);
  // Stopped by Ctrl+Z before it stored anything: the undo's notice says more than "cancelled".
  if (by_undo && !found) state.notice = undo_notice;
  if (by_undo && found) {
    // Ctrl+Z came after the run's last place to stop, as it stored its suggestions: they are
    // taken back, as the cancel promised.
    try {
      if (state.document && state.document->path == found->document)
        state.document->label_store().undo(labelling.annotator);
      state.notice =
          found->method + " cancelled (Ctrl+Z): its suggestions, stored as it ended, are undone";
    } catch (const std::exception& error) {
      fail(state, error.what());
    }
    if (state.document) state.document->reload_labels();
    return;
  }
  if (!found || !state.document || state.document->path != found->document) return;
  after_edit(state, 0,
             found->method + ": " + std::to_string(found->added) + " suggestions" +
                 (found->rejected > 0 ? " (" + std::to_string(found->rejected) + " rejected before)"
                                      : "") +
                 "; A accepts, R rejects");
  select_next_suggestion(state, found->annotator, -1e300);
}

}  // namespace

bool fit_segmenter_to_labels(WorkbenchState& state) {
  if (!state.document) return false;
  Document& document = *state.document;
  try {
    LabelFilter filter;
    filter.recording = document.recording_id();
    filter.source = LabelSource::kManual;
    filter.annotator = state.labelling.annotator;
    std::vector<Label> touches = document.label_store().list(filter);
    if (touches.size() < 3)
      return fail(state, "Fit needs at least three touches labelled in your lane (" +
                             state.labelling.annotator + "); it has " +
                             std::to_string(touches.size()) + ": label more, then fit again");
    const std::string presets = segmenter_presets_path(document.label_store().path());
    start_job<LabellingState::SegmenterFitted>(
        state, "fit segmenter", "fit segmenter",
        [read = recording_for_job(document, 0.0, 0.3), layout = document.layout,
         touches = std::move(touches), presets, path = document.path,
         lane = state.labelling.active_lane()](JobProgress& progress) {
          const Recording whole = read(progress);
          progress.report(0.3, "trying parameter sets");
          SegmenterFit fit = fit_segmenter({{&whole, &layout, touches}}, [&](double share) {
            progress.report(0.3 + 0.65 * share, "trying parameter sets");
            progress.check();
          });
          save_segmenter_preset(presets, fit_preset(fit, "fitted", lane));
          return LabellingState::SegmenterFitted{path, std::move(fit)};
        },
        apply_finished_fit);
    state.error.clear();
    state.notice = "fitting the segmenter to your labels...";
    return true;
  } catch (const std::exception& error) {
    return fail(state, error.what());
  }
}

namespace {

void apply_finished_fit(WorkbenchState& state, Job<LabellingState::SegmenterFitted>& job) {
  std::optional<LabellingState::SegmenterFitted> fitted = job_result(state, job);
  if (!fitted) return;
  const SegmenterFit& fit = fitted->fit;
  state.labelling.last_segmenter = fit.method;
  state.labelling.segmenter_params.fill('\0');
  fit.params.copy(state.labelling.segmenter_params.data(),
                  state.labelling.segmenter_params.size() - 1);
  // The parameters serve every recording of the skin; say where they came from when the
  // operator has opened another meanwhile.
  const bool elsewhere = !state.document || state.document->path != fitted->document;
  state.notice = "segmenter fitted to " + std::to_string(fit.touches) + " touches" +
                 (elsewhere ? " of " + std::filesystem::path(fitted->document).filename().string()
                            : std::string()) +
                 ": " + fit.params + " (held out " + fit.folds + ": event F1 " +
                 fixed_text(fit.held_out.events.f1(), 2) + "); G suggests with it";
}

}  // namespace

bool accept_suggestion(WorkbenchState& state) {
  const std::optional<Label> selected = selected_label(state);
  if (!selected || selected->source != LabelSource::kSegmenter)
    return fail(state, "select a suggestion (a segmenter's label) to accept");
  std::string class_name = state.labelling.pending_class;
  if (class_name.empty() && selected->class_name != kUnknownClass)
    class_name = selected->class_name;
  if (class_name.empty()) return fail(state, "choose the class with 1-9, then A");
  if (!apply_command(state, adopt_edit(*selected, class_name, state.labelling.annotator)))
    return false;
  state.labelling.pending_class.clear();
  after_edit(state, 0, "accepted " + class_name + " " + format_seconds(selected->t0));
  select_next_suggestion(state, selected->annotator, selected->t0);
  return true;
}

bool reject_suggestion(WorkbenchState& state) {
  const std::optional<Label> selected = selected_label(state);
  if (!selected || selected->source != LabelSource::kSegmenter)
    return fail(state, "select a suggestion (a segmenter's label) to reject");
  if (!apply_command(state, reject_edit(*selected))) return false;
  after_edit(state, 0, "rejected the suggestion at " + format_seconds(selected->t0));
  select_next_suggestion(state, selected->annotator, selected->t0);
  return true;
}

bool move_label_bounds(WorkbenchState& state, int64_t id, double t0, double t1) {
  if (!state.document) return false;
  std::optional<Label> label;
  for (const Label& candidate : state.document->labels)
    if (candidate.id == id) label = candidate;
  if (!label || !own(state, *label)) return fail(state, "only your own labels are moved");
  if (!(t0 < t1)) return fail(state, "a label must end after it starts");
  if (!apply_command(state, bounds_edit(*label, t0, t1))) return false;
  after_edit(
      state, id,
      "label " + std::to_string(id) + " now " + format_seconds(t0) + " to " + format_seconds(t1));
  return true;
}

namespace {

// Where the skin's signal (the shown modality) starts or stops moving near t.
std::vector<double> onsets_near(WorkbenchState& state, double t, double tolerance) {
  const Document& document = *state.document;
  const std::vector<int> columns =
      taxel_columns(document.layout, document.samples().info().channels, state.modality);
  return activity_edges(document.samples(), columns, current_rest_scale(state, columns), t,
                        tolerance);
}

}  // namespace

double snapped(WorkbenchState& state, double t, double tolerance) {
  if (!state.labelling.snap || !state.document) return t;
  // Boundaries of labels first (decisions already made), the signal's onsets second.
  double best = t, distance = tolerance;
  const Lanes& lanes = state.document->lanes;
  for (size_t k = 0; k < lanes.keys.size(); ++k) {
    if (lanes.keys[k].id() == state.labelling.active_lane()) continue;
    for (size_t index : lanes.lanes[k].meeting(t - tolerance, t + tolerance))
      for (double edge : {lanes.lanes[k].labels()[index].t0, lanes.lanes[k].labels()[index].t1})
        if (std::fabs(edge - t) < distance) distance = std::fabs(edge - t), best = edge;
  }
  if (best != t) return best;
  for (double onset : onsets_near(state, t, tolerance))
    if (std::fabs(onset - t) < distance) distance = std::fabs(onset - t), best = onset;
  return best;
}

bool walk_labels(WorkbenchState& state, int direction) {
  const LaneIndex* lane = active_lane(state);
  if (!lane) return fail(state, "your lane (" + state.labelling.annotator + ") has no labels yet");
  // From the cursor; from the selected label's start when the cursor is inside it.
  double from = state.clock.time();
  if (const auto selected = selected_label(state);
      selected && own(state, *selected) && from >= selected->t0 && from < selected->t1)
    from = selected->t0;
  const int64_t index = direction > 0 ? lane->next_after(from) : lane->previous_before(from);
  if (index < 0) return fail(state, direction > 0 ? "no later label" : "no earlier label");
  const Label& label = lane->labels()[static_cast<size_t>(index)];
  state.selection.labels = {label.id};
  state.clock.seek(label.t0);
  state.error.clear();
  return true;
}

void draw_class_picker(WorkbenchState& state) {
  LabellingState& labelling = state.labelling;
  if (!state.document) return;
  if (labelling.picker_open) {
    ImGui::OpenPopup("class_picker");
    labelling.picker_open = false;
  }
  if (!ImGui::BeginPopup("class_picker")) return;
  // Type part of a class name; Enter takes the first match, Escape closes.
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  const bool entered =
      ImGui::InputTextWithHint("##class", "class...", labelling.picker_text.data(),
                               labelling.picker_text.size(), ImGuiInputTextFlags_EnterReturnsTrue);
  remember_item(state, "picker:text",
                "Type part of a class name; Enter takes the first match, Escape closes");
  const std::string typed = labelling.picker_text.data();
  std::vector<std::string> matches;
  for (const std::string& name : state.document->classes)
    if (name.find(typed) != std::string::npos) matches.push_back(name);
  for (const std::string& name : matches)
    if (ImGui::Selectable(name.c_str())) {
      labelling.pending_class = name;
      ImGui::CloseCurrentPopup();
    }
  if (entered && !matches.empty()) {
    labelling.pending_class = matches.front();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void apply_dragged_bounds(WorkbenchState& state) {
  if (!state.document) return;
  if (auto move = std::exchange(state.labelling.move_request, std::nullopt))
    move_label_bounds(state, std::get<0>(*move), std::get<1>(*move), std::get<2>(*move));
}

}  // namespace tactile
