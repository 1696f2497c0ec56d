// Live mode: connect, take what arrived each frame, follow, record (docs/LIVE.md).
#include "live.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <utility>

#include "gl_texture.h"
#include "tactile/error.h"
#include "tactile/io/disk_room.h"
#include "tactile/signal/display_scale.h"
#include "tactile/signal/taxel_values.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"
#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

constexpr const char* kUnrecorded =
    "live data is not recorded yet: press Ctrl+R to record, then label";

std::string timestamped_name() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char name[64];
  std::strftime(name, sizeof name, "live-%Y%m%d-%H%M%S", &local);
  return name;
}

LiveSampleSource& live_source(WorkbenchState& state) {
  return static_cast<LiveSampleSource&>(*state.document->source);
}

// The plots show the newest `window` seconds and the cursor sits on the newest sample.
void follow(WorkbenchState& state) {
  const SampleSource& source = *state.document->source;
  if (source.sample_count() == 0) return;
  const double end = source.end_time();
  const double start =
      std::max(source.time_of(live_source(state).first_kept()), source.start_time());
  state.clock.set_range(start, end);
  if (!state.live.follow) return;
  state.clock.seek(source.time_of(source.sample_count() - 1));
  state.plot.view_t1 = end;
  state.plot.view_t0 = end - state.live.window_seconds;
  state.plot.fitted = true;
}

// While following, the plot shows the channels that are active now: those of the selected
// taxels when some are selected, else (twice a second) the eight that changed most beyond their
// noise band over the last second; when none did, the plot stays as it is.
void plot_active_channels(WorkbenchState& state) {
  constexpr int kMostChannels = 8;
  constexpr double kEverySeconds = 0.5;
  LiveState& live = state.live;
  const SampleSource& source = *state.document->source;
  const Document& document = *state.document;
  if (!live.follow || !live.channels_chosen || source.sample_count() == 0) return;
  const double newest = source.end_time();
  if (newest < live.active_checked_at + kEverySeconds && newest >= live.active_checked_at) return;
  live.active_checked_at = newest;
  const std::vector<int> columns =
      taxel_columns(document.layout, source.info().channels, state.modality);
  std::vector<char> plotted(static_cast<size_t>(source.channel_count()), 0);
  bool any = false;
  if (!state.selection.taxels.empty()) {
    for (size_t k = 0; k < document.layout.taxels.size() && k < columns.size(); ++k) {
      const int64_t id = document.layout.taxels[k].id;
      if (columns[k] < 0 || std::find(state.selection.taxels.begin(), state.selection.taxels.end(),
                                      id) == state.selection.taxels.end())
        continue;
      plotted[static_cast<size_t>(columns[k])] = 1;
      any = true;
    }
  } else {
    const int64_t count =
        std::min<int64_t>(source.sample_count(), std::llround(std::max(1.0, source.rate_hz())));
    std::vector<int> present;
    for (int column : columns)
      if (column >= 0) present.push_back(column);
    if (present.empty()) return;
    const SampleMatrix window = source.read(present, source.sample_count() - count, count);
    const RestScale& scale = current_rest_scale(state, columns);
    std::vector<std::pair<float, int>> change;
    for (size_t k = 0, p = 0; k < columns.size(); ++k) {
      if (columns[k] < 0) continue;
      const Eigen::Index column = static_cast<Eigen::Index>(p++);
      const float rest = scale.rest[k], band = scale.noise_band[k];
      if (!std::isfinite(rest)) continue;
      float most = 0.0f;
      for (Eigen::Index row = 0; row < window.rows(); ++row)
        if (std::isfinite(window(row, column)))
          most = std::max(most, std::abs(window(row, column) - rest) - band);
      if (most > 0.0f) change.emplace_back(most, columns[k]);
    }
    std::stable_sort(change.begin(), change.end(),
                     [](auto& a, auto& b) { return a.first > b.first; });
    for (size_t k = 0; k < change.size() && k < static_cast<size_t>(kMostChannels); ++k) {
      plotted[static_cast<size_t>(change[k].second)] = 1;
      any = true;
    }
  }
  if (any) state.plotted = std::move(plotted);
}

// The contact detector sees every sample once; a contact starts a recording, a quiet time
// after the last one stops it.
void auto_record(WorkbenchState& state, LiveServices& services) {
  LiveState& live = state.live;
  LiveSampleSource& source = live_source(state);
  if (!live.auto_record) {
    services.detector.reset();
    return;
  }
  if (!services.detector) {
    ContactDetectorOptions options;
    options.quiet_seconds = live.quiet_seconds;
    services.detector =
        std::make_unique<ContactDetector>(source.channel_count(), source.rate_hz(), options);
    live.detected_until = source.sample_count();
  }
  const int64_t count = source.sample_count();
  live.detected_until = std::max(live.detected_until, source.first_kept());
  bool began = false;
  for (; live.detected_until < count; ++live.detected_until) {
    services.detector->add(source.values_at(live.detected_until));
    began = began || services.detector->contact_began();
  }
  if (began && !services.recorder) start_recording(state, services, "");
  if (services.recorder && live.recorder_automatic && services.detector->quiet_for_long())
    stop_recording(state, services);
}

// Online decisions: each goes into the transient "online" lane (add_online_decision) and the
// newest is written over the skin.
void classify(WorkbenchState& state, LiveServices& services) {
  LiveState& live = state.live;
  if (!services.online) return;
  services.online->update(live_source(state));
  std::vector<OnlineDecision> decisions = services.online->take();
  if (decisions.empty()) return;
  Document& document = *state.document;
  // The lane holds what the buffer holds.
  const double oldest = document.source->time_of(live_source(state).first_kept());
  for (OnlineDecision& decision : decisions) {
    add_online_decision(document.transient_labels, decision, document.recording_id(), oldest);
    live.shown = decision;
    live.decisions.push_back(std::move(decision));
  }
  if (live.decisions.size() > 2000)
    live.decisions.erase(live.decisions.begin(), live.decisions.end() - 1000);
  document.reload_labels();
  if (const std::string failure = services.online->error(); !failure.empty())
    state.notice = "online model: " + failure;
}

// The camera beside the skin: opened with the live source; a camera that cannot be opened is
// named and the skin goes on without it.
void open_camera(WorkbenchState& state, LiveServices& services, const std::string& url) {
  LiveState::CameraShown shown;
  shown.url = url;
  try {
    CameraOptions options;
    options.url = url;
    options.pre_trigger = state.live.pretrigger_seconds;
    services.camera =
        std::make_unique<Camera>(options, [clock = services.clock] { return clock->now(); });
  } catch (const std::exception& failure) {
    shown.error = failure.what();
    state.error = "camera: " + shown.error;
  }
  state.live.camera = std::move(shown);
}

void poll_camera(WorkbenchState& state, LiveServices& services) {
  if (!services.camera || !state.live.camera) return;
  LiveState::CameraShown& shown = *state.live.camera;
  shown.received = services.camera->frames_received();
  if (std::shared_ptr<const VideoFrame> frame = services.camera->latest()) shown.frame = frame;
  if (const std::string failure = services.camera->error();
      !failure.empty() && failure != shown.error) {
    shown.error = failure;
    state.error = "camera: " + failure;
  }
}

// The camera's video beside a recording that starts now, its pre-trigger frames first, attached
// to the recording with the offset of its first frame on the recording's clock.
void record_camera(WorkbenchState& state, LiveServices& services, const std::string& recording) {
  if (!services.camera || !state.live.camera) return;
  const fs::path file(recording);
  const std::string video = (file.parent_path() / (file.stem().string() + "-camera.mp4")).string();
  try {
    VideoAttachment attachment;
    attachment.name = "camera";
    attachment.path = kept_video_path(recording, video);
    attachment.offset = services.camera->start_recording(video);
    write_attachments(recording, {attachment});
    state.live.camera->recording = video;
  } catch (const std::exception& failure) {
    state.error = "camera not recorded: " + std::string(failure.what());
  }
}

}  // namespace

bool load_online_model(WorkbenchState& state, LiveServices& services, const std::string& path) {
  LiveState& live = state.live;
  if (!services.receiver || !state.document) return false;
  try {
    SavedModel model = read_model_file(path);
    const SkinLayout& layout = state.document->layout;
    services.online =
        std::make_unique<OnlineClassifier>(std::move(model), layout, state.document->source->info(),
                                           default_online_options(layout.id));
    live.model_path = path;
    live.decisions.clear();
    live.shown.reset();
    state.document->transient_labels.clear();
    state.notice = "classifying with " + path;
    return true;
  } catch (const std::exception& failure) {
    state.error = std::string("cannot classify live: ") + failure.what();
    return false;
  }
}

bool connect_live(WorkbenchState& state, LiveServices& services, const std::string& url,
                  const std::string& skin_option) {
  try {
    const LiveAddress address = parse_live_address(url, "--connect");
    disconnect_live(state, services);  // its port or device may be the one asked for again
    std::unique_ptr<DatagramInput> input = open_live_input(address);
    std::string skin = skin_option.empty() ? input->skin() : skin_option;
    if (skin.empty())
      throw Error("--skin", "is needed for " + address.scheme + " sources (" +
                                joined(packet_skin_ids()) + ")");
    if (!input->skin().empty() && input->skin() != skin)
      throw Error("--skin", skin + " does not match the source's skin " + input->skin());
    SkinLayout layout = load_layout(skin);
    auto receiver = std::make_unique<LiveReceiver>(std::move(input), layout);
    SourceInfo info = receiver->source_info();
    info.recording_id = "live";
    const auto capacity =
        std::max<int64_t>(1, std::llround(state.live.buffer_seconds * info.rate_hz));
    auto document = std::make_unique<Document>();
    document->source = std::make_unique<LiveSampleSource>(info, capacity);
    document->layout = std::move(layout);
    document->classes = document->layout.classes;
    document->labels_refused = kUnrecorded;
    document->streams = {"skin"};
    document->reload_labels();
    state.document = std::move(document);
    services.receiver = std::move(receiver);
    state.live.connected = true;
    state.live.url = url;
    state.live.listening = address.scheme == "udp" ? services.receiver->describe() : "";
    state.live.follow = true;
    state.live.counters = {};
    state.live.channels_chosen = false;
    if (state.workspace.empty()) state.workspace = fs::current_path().string();
    state.selection = {};
    state.modality =
        std::max(0, state.document->layout.modality_index(state.document->layout.display_modality));
    plot_moving_channels(state);  // the first channels until data has come
    state.rest_scale_modality = -1;
    state.plot = SignalPlotState{};
    state.plot.fitted = true;
    state.clock.pause();
    state.error.clear();
    state.notice = "connected to " + url;
    services.clock = std::make_shared<LiveClock>();
    if (!state.options.camera.empty()) open_camera(state, services, state.options.camera);
    return true;
  } catch (const std::exception& failure) {
    state.error = std::string("cannot connect: ") + failure.what();
    return false;
  }
}

void disconnect_live(WorkbenchState& state, LiveServices& services) {
  if (!services.receiver) return;
  if (services.recorder) stop_recording(state, services);
  services.camera.reset();
  if (state.live.camera) delete_texture(state.live.camera->texture.id);
  state.live.camera.reset();
  services.online.reset();
  services.receiver->stop();
  services.receiver.reset();
  services.detector.reset();
  state.live.connected = false;
  state.live.model_path.clear();
}

void poll_live(WorkbenchState& state, LiveServices& services) {
  LiveState& live = state.live;
  if (!services.receiver || !state.document) return;
  if (std::exchange(live.resize_request, false)) {
    const std::string url = live.url, skin = state.document->layout.id, model = live.model_path;
    if (!connect_live(state, services, url, skin)) return;
    if (!model.empty()) load_online_model(state, services, model);
  }
  // The requests of the last frame's live bar and keys.
  if (std::exchange(live.record_request, false)) {
    if (services.recorder)
      stop_recording(state, services);
    else
      start_recording(state, services, "");
  }
  if (auto model = std::exchange(live.classify_request, std::nullopt))
    load_online_model(state, services, *model);
  if (std::exchange(live.clear_request, false)) {
    live_source(state).clear();
    live.detected_until = 0;
  }
  LiveSampleSource& source = live_source(state);
  services.receiver->ring().drain(
      [&](double time, std::span<const float> values) { source.add(time, values); });
  live.counters = services.receiver->counters();
  if (source.sample_count() > 0) services.clock->set(source.end_time());
  poll_camera(state, services);
  if (const std::string failure = services.receiver->failure();
      !failure.empty() && live.failure != failure) {
    live.failure = failure;
    state.error = "live source failed: " + failure;
  }
  // Once two seconds have arrived: plot the channels that move and learn the rest level.
  if (!live.channels_chosen && source.duration() >= 2.0) {
    live.channels_chosen = true;
    plot_moving_channels(state);
    live.scale_learnt_at = -1.0;
  }
  // The colour scale learnt again every two seconds over the whole buffer, as a replay learns it
  // over the whole file: learnt once from the first two seconds, it stayed at their noise.
  constexpr double kLearnEverySeconds = 2.0;
  if (source.sample_count() > 0 &&
      (source.end_time() >= live.scale_learnt_at + kLearnEverySeconds ||
       source.end_time() < live.scale_learnt_at)) {
    live.scale_learnt_at = source.end_time();
    const bool same = state.rest_scale_modality == state.modality;
    const std::vector<int> columns =
        taxel_columns(state.document->layout, source.info().channels, state.modality);
    state.rest_scale = live_rest_scale(source, columns, same ? state.rest_scale.max_change : 0.0);
    state.rest_scale_modality = state.modality;
  }
  plot_active_channels(state);
  auto_record(state, services);
  classify(state, services);
  if (services.recorder) {
    services.recorder->take(source);
    live.recorded_samples = services.recorder->samples_taken();
    live.room = services.recorder->room();
    if (const std::string failure = services.recorder->error(); !failure.empty()) {
      state.error = "recording failed: " + failure +
                    ". What was flushed is in the file; `tactile repair " +
                    services.recorder->path() + "` rebuilds the rest and says what was lost";
      stop_recording(state, services);
    } else if (services.recorder->stopped()) {
      state.error = live.room.stopped;
      stop_recording(state, services);
    }
  }
  follow(state);
}

bool start_recording(WorkbenchState& state, LiveServices& services, const std::string& requested) {
  LiveState& live = state.live;
  if (!services.receiver || services.recorder) return false;
  std::string path = requested;
  if (path.empty()) {
    const fs::path folder =
        live.record_folder.empty() ? fs::path(state.workspace) : fs::path(live.record_folder);
    path = (folder / (timestamped_name() + ".h5")).string();
    for (int k = 2; fs::exists(path); ++k)
      path = (folder / (timestamped_name() + "-" + std::to_string(k) + ".h5")).string();
  }
  try {
    LiveRecorderOptions options;
    options.pretrigger_seconds = live.pretrigger_seconds;
    options.metadata["source"] = live.url;
    services.recorder = std::make_unique<LiveRecorder>(path, live_source(state), options);
  } catch (const std::exception& failure) {
    state.error = std::string("cannot record: ") + failure.what();
    return false;
  }
  live.recorder_automatic = live.auto_record && requested.empty() && services.detector &&
                            services.detector->state() == ContactDetector::State::kContact;
  live.recording = services.recorder->path();
  live.recorded_samples = 0;
  record_camera(state, services, path);
  // Labels made from now on belong to this recording, in the label database beside it.
  Document& document = *state.document;
  document.path = fs::absolute(path).lexically_normal().string();
  document.live_recording_id = services.recorder->recording_id();
  document.labels_refused.clear();
  document.store.reset();
  document.labels_path = (fs::path(document.path).parent_path() / "labels.db").string();
  document.reload_labels();
  state.notice = "recording " + path;
  return true;
}

bool stop_recording(WorkbenchState& state, LiveServices& services) {
  LiveState& live = state.live;
  if (!services.recorder) return false;
  const std::string path = services.recorder->path();
  try {
    services.recorder->finish(live_source(state));
    state.notice = "recorded " + path + " (" + std::to_string(services.recorder->samples_taken()) +
                   " samples)";
  } catch (const std::exception& failure) {
    state.error = std::string("recording ended with an error: ") + failure.what();
  }
  live.recorded.push_back(path);
  services.recorder.reset();
  if (services.camera && live.camera && !live.camera->recording.empty()) {
    services.camera->stop_recording();
    live.camera->recording.clear();
  }
  live.recording.clear();
  // Labels stay possible for what was just recorded until the next recording starts: the
  // document keeps the path and recording id of the last one.
  return true;
}

void draw_live_bar(WorkbenchState& state) {
  LiveState& live = state.live;
  const LiveCounters& counters = live.counters;
  const bool recording = !live.recording.empty();
  const ImGuiStyle& style = ImGui::GetStyle();
  ImGui::TextColored(
      live.failure.empty() ? ImVec4(0.3f, 0.9f, 0.4f, 1.0f) : ImVec4(1.0f, 0.4f, 0.35f, 1.0f),
      live.failure.empty() ? "LIVE" : "FAILED");
  ImGui::SameLine();
  ImGui::TextUnformatted(live.url.c_str());
  ImGui::SameLine();
  if (ImGui::Checkbox("follow (F)", &live.follow) && live.follow) state.plot.fitted = true;
  remember_item(state, "checkbox:follow",
                "Keep the newest sample in view (F); off: stay where the view is");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputFloat("buffer s", &live.buffer_seconds, 0, 0, "%.0f");
  remember_item(state, "input:buffer",
                "Seconds of the stream kept in memory to scroll back through");
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    live.buffer_seconds = std::clamp(live.buffer_seconds, 1.0f, 86400.0f);
    // A new length is a new buffer: at the next frame's start the source is connected again
    // (what was held is dropped; not while recording).
    live.resize_request = !recording;
  }
  remember_item(state, "input:buffer");
  ImGui::SameLine();
  if (ImGui::Button("Clear")) live.clear_request = true;
  remember_item(state, "button:clear", "Forget what the buffer holds (a recording keeps its file)");
  ImGui::SameLine();
  if (ImGui::Button(recording ? "Stop recording (Ctrl+R)" : "Record (Ctrl+R)"))
    live.record_request = true;
  remember_item(state, "button:record",
                "Record the stream into a new file in the workspace, with the pre-trigger's "
                "seconds (Ctrl+R)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(50);
  ImGui::InputFloat("pre s", &live.pretrigger_seconds, 0, 0, "%.0f");
  remember_item(state, "input:pretrigger",
                "Seconds before the press of Record that the file starts with");
  live.pretrigger_seconds = std::clamp(live.pretrigger_seconds, 0.0f, 600.0f);
  same_line_if_fits(ImGui::GetFrameHeight() + style.ItemInnerSpacing.x +
                    ImGui::CalcTextSize("start on contact").x);
  ImGui::Checkbox("start on contact", &live.auto_record);
  remember_item(state, "checkbox:auto-record",
                "Start a recording when a contact begins, stop it after a quiet time");
  // The model's field and Classify together, on the next line when they do not fit (at 1280
  // x 720 Classify was cut off at the view's edge).
  same_line_if_fits(160.0f + style.ItemSpacing.x + ImGui::CalcTextSize("Classify").x +
                    2 * style.FramePadding.x);
  ImGui::SetNextItemWidth(160);
  ImGui::InputTextWithHint("##model", "model.json", live.model_input.data(),
                           live.model_input.size());
  remember_item(state, "input:model",
                "A saved model (tactile evaluate --save-model) to classify the stream with");
  ImGui::SameLine();
  if (ImGui::Button("Classify")) live.classify_request = std::string(live.model_input.data());
  remember_item(state, "button:classify",
                "Classify each touch of the stream with the model (a lane of decisions)");
  // Second line: what arrived and what did not.
  const SampleSource& source = *state.document->source;
  ImGui::Text("%s  received %lld   lost %lld   duplicated %lld   reordered %lld   broken %lld",
              format_seconds(source.duration()).c_str(), static_cast<long long>(counters.datagrams),
              static_cast<long long>(counters.lost), static_cast<long long>(counters.duplicated),
              static_cast<long long>(counters.reordered), static_cast<long long>(counters.broken));
  if (ImGui::IsItemHovered() && !counters.last_error.empty())
    ImGui::SetTooltip("last broken datagram: %s", counters.last_error.c_str());
  if (counters.overflow > 0) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1.0f, 0.65f, 0.2f, 1.0f), "behind: %lld samples dropped",
                       static_cast<long long>(counters.overflow));
  }
  // Faults of the device and the sender: only once one happened, so a calm stream stays calm.
  if (counters.unplugs + counters.restarts + counters.stalls + counters.clock_jumps > 0) {
    ImGui::SameLine();
    ImGui::TextColored(
        ImVec4(1.0f, 0.65f, 0.2f, 1.0f),
        "unplugged %lld   replugged %lld   restarts %lld   stalls %lld   clock jumps %lld",
        static_cast<long long>(counters.unplugs), static_cast<long long>(counters.replugs),
        static_cast<long long>(counters.restarts), static_cast<long long>(counters.stalls),
        static_cast<long long>(counters.clock_jumps));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "unplugged/replugged: the device went away and came back\n"
          "restarts: the sender's count started over\n"
          "stalls: silences longer than ten datagram periods\n"
          "clock jumps: the sender's time stamps jumped; its samples were placed by their sequence "
          "numbers");
  }
  if (!counters.gone.empty()) {
    ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.35f, 1.0f),
                       "device gone, waiting for it to come back: %s", counters.gone.c_str());
  } else if (counters.stalled) {
    ImGui::TextColored(ImVec4(1.0f, 0.65f, 0.2f, 1.0f),
                       "no data from %s for a while: waiting (the gap will show)",
                       live.url.c_str());
  }
  if (recording) {
    ImGui::SameLine();
    ImGui::TextColored(
        ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "REC %s %s", fs::path(live.recording).filename().c_str(),
        format_seconds(static_cast<double>(live.recorded_samples) / source.rate_hz()).c_str());
    if (live.room.low) {
      ImGui::SameLine();
      const double left = live.room.minutes_left;
      char time_left[32];
      std::snprintf(time_left, sizeof time_left, left < 1.0 ? "%.0f s" : "%.0f min",
                    left < 1.0 ? left * 60.0 : std::floor(left));
      ImGui::TextColored(ImVec4(1.0f, 0.65f, 0.2f, 1.0f), "disk: %s left at %s/s (%s free)",
                         time_left,
                         byte_text(static_cast<int64_t>(live.room.bytes_per_second)).c_str(),
                         byte_text(live.room.free_bytes).c_str());
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "The recording stops by itself, with a whole file, before its disk is full.");
    }
  }
}

nlohmann::json live_json(const WorkbenchState& state) {
  const LiveState& live = state.live;
  if (!live.connected) return nullptr;
  const LiveCounters& counters = live.counters;
  nlohmann::json json;
  json["source"] = live.url;
  json["listening"] =
      live.listening.empty() ? nlohmann::json(nullptr) : nlohmann::json(live.listening);
  json["received"] = counters.datagrams;
  json["samples"] = state.document ? state.document->source->sample_count() : 0;
  json["lost"] = counters.lost;
  json["duplicated"] = counters.duplicated;
  json["reordered"] = counters.reordered;
  json["broken"] = counters.broken;
  json["behind"] = counters.overflow;
  json["restarts"] = counters.restarts;
  json["unplugs"] = counters.unplugs;
  json["replugs"] = counters.replugs;
  json["stalls"] = counters.stalls;
  json["stalled"] = counters.stalled;
  json["clock_jumps"] = counters.clock_jumps;
  json["late_dropped"] = counters.late_dropped;
  json["gone"] = counters.gone;
  json["gap_samples"] =
      state.document ? static_cast<const LiveSampleSource&>(*state.document->source).gap_samples()
                     : 0;
  json["follow"] = live.follow;
  json["buffer_seconds"] = live.buffer_seconds;
  json["camera"] = nullptr;
  if (const std::optional<LiveState::CameraShown>& camera = live.camera)
    json["camera"] = {{"url", camera->url},
                      {"received", camera->received},
                      {"frame_time", camera->frame ? nlohmann::json(camera->frame->time)
                                                   : nlohmann::json(nullptr)},
                      {"error", camera->error},
                      {"recording", camera->recording}};
  json["newest"] = state.document && state.document->source->sample_count() > 0
                       ? nlohmann::json(state.document->source->time_of(
                             state.document->source->sample_count() - 1))
                       : nlohmann::json(nullptr);
  json["recording"] =
      live.recording.empty() ? nlohmann::json(nullptr) : nlohmann::json(live.recording);
  json["recorded_samples"] = live.recording.empty() ? 0 : live.recorded_samples;
  json["disk_free_bytes"] = live.room.free_bytes;
  json["disk_minutes_left"] = live.room.minutes_left;
  json["disk_low"] = live.room.low;
  json["recorded"] = live.recorded;
  json["failure"] = live.failure;
  json["model"] = live.model_path;
  nlohmann::json predictions = nlohmann::json::array();
  const size_t first = live.decisions.size() > 20 ? live.decisions.size() - 20 : 0;
  for (size_t k = first; k < live.decisions.size(); ++k) {
    const OnlineDecision& decision = live.decisions[k];
    predictions.push_back({{"time", decision.t1},
                           {"t0", decision.t0},
                           {"class", decision.class_name},
                           {"score", decision.score},
                           {"final", decision.final}});
  }
  json["predictions"] = predictions;
  return json;
}

}  // namespace tactile
