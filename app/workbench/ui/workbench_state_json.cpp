// The workbench's state as JSON, for scripts (docs/SCRIPTING.md, "state").
#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "files.h"
#include "jobs.h"
#include "keys.h"
#include "labelling.h"
#include "live.h"
#include "results.h"
#include "tactile/signal/taxel_values.h"
#include "tactile/skins/skin.h"
#include "video.h"
#include "views.h"
#include "workbench.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

// The videos: each one's attachment, what it shows now and why it cannot show more.
nlohmann::json videos_json(const WorkbenchState& state) {
  nlohmann::json videos = nlohmann::json::array();
  for (const VideoState::Shown& shown : state.video.videos) {
    const VideoAttachment& attachment = shown.attachment;
    const double video_time = attachment.video_time(state.clock.time());
    nlohmann::json entry = {{"name", attachment.name},
                            {"path", attachment.path},
                            {"file", shown.path},
                            {"offset", attachment.offset},
                            {"rate", attachment.rate},
                            {"video_time", video_time},
                            {"wanted_frame", shown.player->wanted()},
                            {"frame", nullptr},
                            {"frame_time", nullptr},
                            {"drawn_frame", static_cast<int64_t>(shown.texture.key)},
                            {"problem", shown.player->problem()}};
    if (const std::shared_ptr<const VideoFrame> frame = shown.player->shown()) {
      entry["frame"] = frame->index;
      entry["frame_time"] = frame->time;
    }
    if (const std::shared_ptr<const VideoInfo> info = shown.player->info()) {
      entry["codec"] = info->codec;
      entry["width"] = info->width;
      entry["height"] = info->height;
      entry["duration"] = info->duration;
      entry["frames"] = info->frame_count;
      entry["rate_fps"] = info->mean_rate;
      entry["variable_rate"] = info->variable_rate;
      if (entry["problem"] == "")
        entry["problem"] = video_time_problem(*info, video_time, attachment.offset);
    }
    videos.push_back(std::move(entry));
  }
  nlohmann::json json = {{"list", videos},
                         {"selected", state.video.selected},
                         {"problem", state.video.problem},
                         {"undo", state.video.undo.size()},
                         {"mark", nullptr},
                         {"region", nullptr},
                         {"proposal", nullptr}};
  if (const std::optional<VideoRegion>& region = state.video.region)
    json["region"] = {{"video", state.video.region_for},
                      {"x", region->x},
                      {"y", region->y},
                      {"width", region->width},
                      {"height", region->height}};
  if (state.video.mark) json["mark"] = {state.video.mark->first, state.video.mark->second};
  if (const std::optional<SyncProposal>& proposal = state.video.proposal)
    json["proposal"] = {{"video", state.video.proposal_for},
                        {"offset", proposal->offset},
                        {"correlation", proposal->correlation},
                        {"confidence", proposal->confidence},
                        {"sure", proposal->sure},
                        {"why", proposal->why}};
  return json;
}

}  // namespace

bool Workbench::jobs_running() const {
  // Until its result is applied on the window's thread: a job that has just ended is still
  // "running" for a screenshot, whose frame must show the result, not the progress.
  // A video's frame at the cursor is decoded on its player's worker: shown once drawn.
  return !pending_jobs(state_).empty() || !videos_caught_up(state_);
}

nlohmann::json Workbench::state_json() const {
  nlohmann::json json;
  const Document* document = state_.document.get();
  json["recording"] = document ? nlohmann::json(document->recording_id()) : nlohmann::json(nullptr);
  json["path"] = document ? nlohmann::json(document->path) : nlohmann::json(nullptr);
  json["stream"] =
      document ? nlohmann::json(document->samples().info().stream) : nlohmann::json(nullptr);
  json["layout"] = document ? nlohmann::json(document->layout.id) : nlohmann::json(nullptr);
  json["time"] = state_.clock.time();
  json["playing"] = state_.clock.playing();
  json["speed"] = state_.clock.speed();
  json["duration"] = document ? document->samples().duration() : 0.0;
  json["label_table"] = {{"sort", state_.label_table.column},
                         {"ascending", state_.label_table.ascending},
                         {"ids", state_.label_table.ids}};
  json["selection"] = {{"labels", state_.selection.labels},
                       {"taxels", state_.selection.taxels},
                       {"segments", state_.selection.segments}};
  nlohmann::json plotted = nlohmann::json::array();
  if (document)
    for (size_t k = 0; k < state_.plotted.size(); ++k)
      if (state_.plotted[k]) plotted.push_back(document->samples().info().channels[k]);
  json["plotted"] = plotted;
  json["modality"] =
      document && !document->layout.modalities.empty()
          ? nlohmann::json(document->layout.modalities[static_cast<size_t>(state_.modality)])
          : nlohmann::json(nullptr);
  json["plot"] = {
      {"t0", state_.plot.view_t0}, {"t1", state_.plot.view_t1}, {"stacked", state_.plot.stacked}};
  json["skin_zoom"] = {{"zoom", state_.skin_zoom.zoom},
                       {"pan_x", state_.skin_zoom.pan_x},
                       {"pan_y", state_.skin_zoom.pan_y}};
  nlohmann::json views = nlohmann::json::object();
  for (const auto& [name, rect] : state_.targets.items)
    if (name.starts_with("view:"))
      views[name.substr(5)] = {
          {"x", rect.x0}, {"y", rect.y0}, {"width", rect.width()}, {"height", rect.height()}};
  json["views"] = views;
  // Each legend's swatch of each class as drawn this frame, by view: "lanes", "scatter", ...
  nlohmann::json legends = nlohmann::json::object();
  for (const auto& [name, rect] : state_.targets.items)
    if (name.starts_with("legend:")) {
      const size_t colon = name.find(':', 7);
      legends[name.substr(7, colon - 7)][name.substr(colon + 1)] = {
          {"x", rect.x0}, {"y", rect.y0}, {"width", rect.width()}, {"height", rect.height()}};
    }
  json["legends"] = legends;
  json["tips"] = state_.targets.tips;
  json["help"] = {{"keys", state_.help.keys_open}, {"getting_started", state_.help.about_open}};
  // The sheet of keys as F1 shows it now: each row's keys and what they do.
  for (const KeyBinding& binding : key_bindings())
    json["help"]["sheet"][keys_text(binding)] = key_sheet_text(binding, state_);
  nlohmann::json items = nlohmann::json::array();
  for (const auto& [name, rect] : state_.targets.items) items.push_back(name);
  json["items"] = items;
  nlohmann::json boxes = nlohmann::json::object();
  for (const auto& [name, rect] : state_.targets.boxes)
    boxes[name] = {
        {"x", rect.x0}, {"y", rect.y0}, {"width", rect.width()}, {"height", rect.height()}};
  json["boxes"] = boxes;
  // The skin as drawn: each taxel's box (a touched one's enlarged box), the touched taxels,
  // the names on the map, and the columns of a strip laid in rows (0: as the layout lies).
  const auto box_json = [](const ScreenRect& rect) {
    return nlohmann::json{
        {"x", rect.x0}, {"y", rect.y0}, {"width", rect.width()}, {"height", rect.height()}};
  };
  nlohmann::json skin_taxels = nlohmann::json::object();
  for (const auto& [id, rect] : state_.targets.taxel_boxes)
    skin_taxels[std::to_string(id)] = box_json(rect);
  nlohmann::json skin_names = nlohmann::json::array();
  for (const auto& [name, rect] : state_.targets.skin_names) {
    nlohmann::json entry = box_json(rect);
    entry["id"] = name;
    skin_names.push_back(entry);
  }
  json["skin"] = {
      {"taxels", skin_taxels},
      {"touched", state_.targets.touched_taxels},
      {"names", skin_names},
      {"columns", state_.skin_drawing.columns},
      {"scale",
       {{"min", state_.targets.skin_scale.first}, {"max", state_.targets.skin_scale.second}}}};
  if (const auto caption = state_.targets.items.find("somatosensory:caption");
      caption != state_.targets.items.end())
    json["skin"]["caption"] = box_json(caption->second);
  json["panels"] = {{"sidebar_width", state_.sizes.sidebar_width},
                    {"skin_fraction", state_.sizes.skin_fraction},
                    {"timeline_height", state_.sizes.timeline_height}};
  json["labels"] = document ? document->labels.size() : 0;
  const LabellingState& labelling = state_.labelling;
  auto optional_time = [](const std::optional<double>& t) {
    return t ? nlohmann::json(*t) : nlohmann::json(nullptr);
  };
  json["annotator"] = labelling.annotator;
  json["marks"] = {{"start", optional_time(labelling.mark_start)},
                   {"end", optional_time(labelling.mark_end)},
                   {"class", labelling.pending_class}};
  nlohmann::json lanes = nlohmann::json::array();
  if (document)
    for (size_t k = 0; k < document->lanes.keys.size(); ++k) {
      const std::string id = document->lanes.keys[k].id();
      lanes.push_back({{"id", id},
                       {"title", document->lanes.keys[k].title()},
                       {"labels", document->lanes.lanes[k].size()},
                       {"hidden", labelling.hidden.count(id) > 0},
                       {"collapsed", labelling.collapsed.count(id) > 0}});
    }
  json["lanes"] = lanes;
  const TouchScore& touches = state_.quality.touches;
  json["quality"] = {{"kappa", state_.quality.agreement.kappa},
                     {"f1", state_.quality.agreement.f1},
                     {"disagreements", state_.quality.agreement.disagreements.size()},
                     {"touch_frame_f1", touches.frames.f1()},
                     {"touch_event_f1", touches.events.f1()},
                     {"touches", touches.touches},
                     {"touches_found", touches.events.hits},
                     {"touch_false_alarms", touches.events.false_alarms},
                     {"touches_split", touches.split},
                     {"touches_merged", touches.merged}};
  json["analysis"] = analysis_json();
  json["live"] = live_json(state_);
  json["videos"] = videos_json(state_);
  json["workspace"] = state_.workspace;
  nlohmann::json files = nlohmann::json::array();
  for (const std::string& file : state_.workspace_files)
    files.push_back(fs::path(file).lexically_relative(state_.workspace).string());
  json["workspace_files"] = files;
  nlohmann::json damaged = nlohmann::json::object();
  for (const auto& [file, reason] : state_.damaged)
    damaged[fs::path(file).lexically_relative(state_.workspace).string()] = reason;
  json["damaged"] = damaged;
  json["label_problems"] = document ? document->label_problems : std::vector<std::string>{};
  json["memory_bytes"] = document ? document->samples().memory_bytes() : 0;
  json["error"] = state_.error;
  json["notice"] = state_.notice;
  // What G runs (Labels > Run segmenter, or a fitted segmenter).
  json["segmenter"] = {{"method", state_.labelling.last_segmenter},
                       {"params", std::string(state_.labelling.segmenter_params.data())}};
  json["unavailable"] = state_.unavailable;
  json["labels_read_only"] = document ? document->labels_read_only : std::string();
  json["labels_path"] = document ? document->labels_path : std::string();
  json["longest_frame_seconds"] = state_.longest_frame_seconds;
  // The frames built since the last state: how many, their median and their longest.
  const std::vector<float>& all = state_.frame_seconds;
  if (all.size() > frames_reported_) {
    std::vector<float> recent(all.begin() + static_cast<std::ptrdiff_t>(frames_reported_),
                              all.end());
    const auto middle = recent.begin() + static_cast<std::ptrdiff_t>(recent.size() / 2);
    std::nth_element(recent.begin(), middle, recent.end());
    json["since_last_state"] = {
        {"frames", recent.size()},
        {"median_frame_seconds", *middle},
        {"longest_frame_seconds", *std::max_element(recent.begin(), recent.end())}};
    frames_reported_ = all.size();
  }
  json["frame"] = state_.frame;
  nlohmann::json jobs = nlohmann::json::array();
  for (const WorkbenchState::JobRecord& record : state_.job_log)
    jobs.push_back({{"name", record.name},
                    {"status", record.status},
                    {"started_frame", record.started_frame},
                    {"finished_frame", record.finished_frame}});
  json["jobs"] = jobs;
  // The list as it stands: every job whose end is not applied yet, and where it is shown.
  nlohmann::json pending = nlohmann::json::array();
  for (const WindowJob& entry : state_.jobs)
    pending.push_back({{"kind", entry.kind},
                       {"name", entry.job->name()},
                       {"status", to_string(entry.job->status())},
                       {"progress", entry.job->progress()},
                       {"shown_in", job_shown_in(entry.kind)}});
  json["pending_jobs"] = pending;
  json["files"] = files_json(state_);
  return json;
}

nlohmann::json Workbench::analysis_json() const {
  const AnalysisState& analysis = state_.analysis;
  nlohmann::json results = nlohmann::json::array();
  for (const ml::PresetOutcome& outcome : analysis.results.rows)
    results.push_back(ml::summary_json(outcome));
  const ml::EvaluationResult* current = current_evaluation(state_);
  const auto class_name = [&](int k) -> nlohmann::json {
    if (!current) return nullptr;
    return k >= 0 && k < static_cast<int>(current->classes.size())
               ? current->classes[static_cast<size_t>(k)]
               : std::string("unknown");
  };
  // The clicked cell's segments as its list shows them, the least sure first.
  nlohmann::json cell_list = nlohmann::json::array();
  for (const size_t k : analysis.confusion.cell_rows) {
    if (!current || k >= current->rows.size()) break;
    const ml::RowPrediction& row = current->rows[k];
    cell_list.push_back({{"recording", row.recording},
                         {"t0", row.t0},
                         {"t1", row.t1},
                         {"segment_id", row.segment_id},
                         {"score", row.score},
                         {"margin", row.margin}});
  }
  nlohmann::json landed = nullptr;
  if (analysis.confusion.landed)
    landed = {{"recording", analysis.confusion.landed->recording},
              {"t0", analysis.confusion.landed->t0},
              {"t1", analysis.confusion.landed->t1},
              {"region", analysis.confusion.landed->region},
              {"true", class_name(analysis.confusion.landed->truth)},
              {"predicted", class_name(analysis.confusion.landed->predicted)},
              {"segment_id", analysis.confusion.landed->segment_id}};
  std::string training = "idle";
  std::string training_progress;
  if (AnyJob* job = find_job(state_, "training")) {
    training = job->status() == JobStatus::kRunning ? "running" : "finished";
    training_progress = progress_text(job->progress(), job->seconds_left());
  }
  nlohmann::json confusion = nullptr;
  if (current) {
    confusion = nlohmann::json::array();
    for (Eigen::Index row = 0; row < current->confusion.rows(); ++row) {
      nlohmann::json counts = nlohmann::json::array();
      for (Eigen::Index column = 0; column < static_cast<Eigen::Index>(current->classes.size());
           ++column)
        counts.push_back(current->confusion(row, column));
      confusion.push_back(counts);
    }
  }
  return {
      {"training", training},
      {"training_progress", training_progress},
      {"results", results},
      {"classes", current ? nlohmann::json(current->classes) : nlohmann::json(nullptr)},
      {"confusion", confusion},
      {"current", current ? nlohmann::json(current->classifier) : nlohmann::json(nullptr)},
      {"classifier_box", std::string(analysis.panel.classifier.data())},
      {"pipeline", analysis.panel.pipeline},  // "" = the skin's own
      {"pipeline_params", std::string(analysis.panel.pipeline_params.data())},
      {"model", analysis.panel.model_path.empty() ? nlohmann::json(nullptr)
                                                  : nlohmann::json(analysis.panel.model_path)},
      {"cell",
       {{"true", analysis.confusion.cell_true < 0 ? nlohmann::json(nullptr)
                                                  : class_name(analysis.confusion.cell_true)},
        {"predicted", analysis.confusion.cell_true < 0
                          ? nlohmann::json(nullptr)
                          : class_name(analysis.confusion.cell_predicted)},
        {"segments", analysis.confusion.cell_rows.size()},
        {"selected", analysis.confusion.cell_selected},
        {"list", cell_list}}},
      {"landed", landed},
      {"dataset_rows", analysis.results.dataset ? analysis.results.dataset->rows() : 0},
      {"som", analysis.som.model ? nlohmann::json({{"rows", analysis.som.model->map().rows},
                                                   {"columns", analysis.som.model->map().columns},
                                                   {"neuron", analysis.som.neuron}})
                                 : nlohmann::json(nullptr)},
      {"somatosensory", analysis.somatosensory.shown},
      {"somatosensory_agreement",
       analysis.somatosensory.agreement
           ? nlohmann::json{{"neighbours", analysis.somatosensory.agreement->neighbours},
                            {"same_part_share", analysis.somatosensory.agreement->same_part_share},
                            {"chance_share", analysis.somatosensory.agreement->chance_share},
                            {"rank_correlation",
                             analysis.somatosensory.agreement->rank_correlation},
                            {"part_share", analysis.somatosensory.agreement->part_share}}
           : nlohmann::json(nullptr)},
      {"somatosensory_taxels",
       analysis.somatosensory.map ? analysis.somatosensory.map->taxels.size() : 0}};
}

}  // namespace tactile
