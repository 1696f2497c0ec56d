#include "video.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "gl_texture.h"
#include "jobs.h"
#include "tactile/cluster/slurm.h"
#include "tactile/error.h"
#include "tactile/live/live_input.h"
#include "tactile/text.h"
#include "tactile/video/video_file.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

constexpr int kShownWidth = 640;   // frames decoded at most this wide: the panel rarely is wider
constexpr int kCachedFrames = 12;  // per video: its worker's cache of decoded frames
constexpr double kProposalRate = 10.0;  // motion and skin activity, samples per second
constexpr double kProposalLag = 30.0;   // seconds either side of the current offset
constexpr double kMarksApart = 0.5;     // seconds between the two instants of a two-point sync

VideoOpenOptions shown_options() {
  VideoOpenOptions options;
  options.max_width = kShownWidth;
  options.cache_frames = kCachedFrames;
  return options;
}

std::vector<VideoAttachment> attachments_of(const VideoState& video) {
  std::vector<VideoAttachment> list;
  for (const VideoState::Shown& shown : video.videos) list.push_back(shown.attachment);
  return list;
}

void release(VideoState& video) {
  for (VideoState::Shown& shown : video.videos) delete_texture(shown.texture.id);
  video.videos.clear();
}

// The shown videos made to match `list`: players kept for files that stay, made for new ones.
void show(WorkbenchState& state, const std::vector<VideoAttachment>& list) {
  VideoState& video = state.video;
  std::vector<VideoState::Shown> next;
  for (const VideoAttachment& attachment : list) {
    const std::string path = video_path(video.recording, attachment);
    auto same = std::find_if(
        video.videos.begin(), video.videos.end(),
        [&](const VideoState::Shown& shown) { return shown.path == path && shown.player; });
    VideoState::Shown entry;
    if (same != video.videos.end()) {
      entry = std::move(*same);
      same->texture = VideoTexture{};  // the texture goes with the entry, not to release()
    } else {
      entry.path = path;
      entry.player = std::make_unique<VideoPlayer>(path, shown_options());
    }
    entry.attachment = attachment;
    next.push_back(std::move(entry));
  }
  release(video);
  video.videos = std::move(next);
  if (video.selected >= video.videos.size()) video.selected = 0;
}

// The recording whose videos are shown: the open one, or the one a live replay streams (its
// samples keep the file's clock, so its videos play with it); "" for other live sources.
std::string shown_recording(const WorkbenchState& state) {
  if (!state.document) return {};
  if (!state.live.connected) return state.document->path;
  try {
    const LiveAddress address = parse_live_address(state.live.url, "--connect");
    if (address.scheme == "replay") return fs::absolute(address.path).lexically_normal().string();
  } catch (const Error&) {
  }
  return {};
}

void load(WorkbenchState& state, const std::string& recording) {
  VideoState& video = state.video;
  release(video);
  video = VideoState{};
  if (recording.empty()) return;
  video.recording = recording;
  try {
    show(state, read_attachments(video.recording));
  } catch (const Error& failure) {
    video.problem = failure.what();
  }
}

int64_t journal_now(const WorkbenchState& state) {
  const LabelStore* store = state.document ? state.document->store.get() : nullptr;
  try {
    return store ? store->last_sequence() : 0;
  } catch (const Error&) {
    return 0;
  }
}

// Writes `list` as the recording's attachments and shows it; the edit is undoable.
bool commit(WorkbenchState& state, std::vector<VideoAttachment> list, const std::string& what) {
  VideoState& video = state.video;
  std::vector<VideoAttachment> before = attachments_of(video);
  try {
    write_attachments(video.recording, list);
  } catch (const Error& failure) {
    return fail(state, "video: " + std::string(failure.what()));
  }
  video.undo.push_back({std::move(before), journal_now(state), what});
  video.redo.clear();
  video.redo_is_video = false;
  show(state, list);
  state.error.clear();
  state.notice = what;
  return true;
}

VideoState::Shown* selected(WorkbenchState& state) {
  VideoState& video = state.video;
  return video.selected < video.videos.size() ? &video.videos[video.selected] : nullptr;
}

std::string offset_words(const VideoAttachment& attachment) {
  std::string words = "offset " + fixed_text(attachment.offset, 3) + " s";
  if (attachment.rate != 1.0) words += ", rate " + significant_text(attachment.rate, 7);
  return words;
}

}  // namespace

bool has_videos(const WorkbenchState& state) {
  return !state.video.videos.empty() || (state.live.connected && state.live.camera);
}

void update_videos(WorkbenchState& state) {
  VideoState& video = state.video;
  const std::string recording = shown_recording(state);
  if (recording != video.recording) load(state, recording);
  const double time = state.clock.time();
  for (VideoState::Shown& shown : video.videos)
    shown.player->want(shown.attachment.video_time(time), state.clock.playing());
}

bool attach_video(WorkbenchState& state, const std::string& path) {
  if (!state.document || state.video.recording.empty() || state.live.connected)
    return fail(state, "attach a video: open a recording first (a live stream records its camera)");
  // Opening indexes every packet: seconds for a long file, so a job; the attachment is written
  // only when the file reads as a video.
  const std::string recording = state.video.recording;
  start_job<VideoInfo>(
      state, "video attach", "attach " + fs::path(path).filename().string(),
      [path](JobProgress&) {
        VideoOpenOptions options;
        options.max_width = 64;
        return VideoFile(path, options).info();
      },
      [recording, path](WorkbenchState& window, Job<VideoInfo>& job) {
        std::optional<VideoInfo> info = job_result(window, job);
        if (!info || window.video.recording != recording) return;
        std::vector<VideoAttachment> list = attachments_of(window.video);
        VideoAttachment attachment;
        attachment.name = free_attachment_name(list, path);
        attachment.path = kept_video_path(recording, path);
        list.push_back(attachment);
        commit(window, list,
               "attached video " + attachment.name + " (" + info->codec + ", " +
                   std::to_string(info->width) + "x" + std::to_string(info->height) + ", " +
                   fixed_text(info->duration, 1) + " s)");
        window.video.selected = window.video.videos.size() - 1;
      });
  return true;
}

bool detach_video(WorkbenchState& state, size_t index) {
  std::vector<VideoAttachment> list = attachments_of(state.video);
  if (index >= list.size()) return fail(state, "no video to detach");
  const std::string name = list[index].name;
  list.erase(list.begin() + static_cast<std::ptrdiff_t>(index));
  return commit(state, list, "detached video " + name + " (its file is kept)");
}

bool set_video_sync(WorkbenchState& state, size_t index, double offset, double rate,
                    const std::string& what) {
  std::vector<VideoAttachment> list = attachments_of(state.video);
  if (index >= list.size()) return fail(state, "no video attached");
  if (!std::isfinite(offset) || !std::isfinite(rate) || rate <= 0.0)
    return fail(state, "video " + list[index].name + ": offset and rate must be finite, rate > 0");
  list[index].offset = offset;
  list[index].rate = rate;
  return commit(state, list,
                "video " + list[index].name + ": " + what + ", " + offset_words(list[index]));
}

bool nudge_video(WorkbenchState& state, double seconds) {
  VideoState::Shown* shown = selected(state);
  if (!shown) return fail(state, "no video attached");
  return set_video_sync(state, state.video.selected, shown->attachment.offset + seconds,
                        shown->attachment.rate, "nudged " + seconds_text(seconds) + " s");
}

double video_frame_seconds(const WorkbenchState& state) {
  const VideoState& video = state.video;
  if (video.selected < video.videos.size())
    if (auto info = video.videos[video.selected].player->info(); info && info->mean_rate > 0)
      return 1.0 / info->mean_rate;
  return 1.0 / 30.0;
}

void step_video_frame(WorkbenchState& state, int direction) {
  VideoState::Shown* shown = selected(state);
  if (!shown) return;
  const std::shared_ptr<const std::vector<double>> times = shown->player->frame_times();
  if (!times || times->empty()) return;
  const VideoAttachment& attachment = shown->attachment;
  const double now = attachment.video_time(state.clock.time());
  const auto after = std::upper_bound(times->begin(), times->end(), now);
  const int64_t current = static_cast<int64_t>(after - times->begin()) - 1;
  const int64_t last = static_cast<int64_t>(times->size()) - 1;
  const int64_t target = std::clamp<int64_t>(current + direction, 0, last);
  state.clock.pause();
  // A hair into the frame, so that rounding of the recording's clock keeps it shown.
  const double into = 1e-6;
  state.clock.seek(attachment.recording_time((*times)[static_cast<size_t>(target)] + into));
}

void mark_video_instant(WorkbenchState& state) {
  VideoState::Shown* shown = selected(state);
  if (!shown) return void(fail(state, "no video attached"));
  VideoState& video = state.video;
  const double recording_time = state.clock.time();
  const double video_time = shown->attachment.video_time(recording_time);
  if (!video.mark) {
    video.mark = {recording_time, video_time};
    state.notice = "video " + shown->attachment.name + ": marked " + fixed_text(recording_time, 3) +
                   " s as seen in both; align a second event and press M again";
    return;
  }
  const auto [first_recording, first_video] = *video.mark;
  if (std::abs(recording_time - first_recording) < kMarksApart)
    return void(fail(state, "mark a second instant at least " + seconds_text(kMarksApart) +
                                " s from the first (" + fixed_text(first_recording, 3) + " s)"));
  VideoAttachment synced = shown->attachment;
  try {
    sync_from_two_points(synced, first_recording, first_video, recording_time, video_time);
  } catch (const Error& failure) {
    video.mark.reset();
    return void(fail(state, failure.what()));
  }
  video.mark.reset();
  set_video_sync(state, video.selected, synced.offset, synced.rate, "synced at two instants");
}

void propose_video_offset(WorkbenchState& state) {
  VideoState::Shown* shown = selected(state);
  if (!shown) return void(fail(state, "no video attached"));
  VideoState& video = state.video;
  video.proposal.reset();
  start_job<VideoState::Proposed>(
      state, "video sync", "propose offset of " + shown->attachment.name,
      [open = source_for_job(*state.document), path = shown->path,
       region = video.region_for == shown->attachment.name ? video.region : std::nullopt,
       centre = shown->attachment.offset, recording = video.recording,
       name = shown->attachment.name](JobProgress& progress) {
        VideoOpenOptions options;
        options.max_width = 160;
        options.grey = true;
        options.cache_frames = 2;
        VideoFile file(path, options);
        const ActivitySeries motion = motion_energy(file, kProposalRate, region,
                                                    progress.steps("the video's motion", 0, 0.7));
        progress.check();
        const ActivitySeries skin =
            skin_activity(*open(), kProposalRate, progress.steps("the skin's activity", 0.7, 0.95));
        return VideoState::Proposed{recording, name,
                                    propose_offset(skin, motion, centre, kProposalLag)};
      },
      [](WorkbenchState& window, Job<VideoState::Proposed>& job) {
        std::optional<VideoState::Proposed> made = job_result(window, job);
        if (!made || made->recording != window.video.recording) return;
        window.video.proposal = made->proposal;
        window.video.proposal_for = made->video;
        const SyncProposal& proposal = made->proposal;
        window.notice = "video " + made->video + ": offset " + fixed_text(proposal.offset, 3) +
                        " s proposed (confidence " + fixed_text(proposal.confidence, 2) + ")" +
                        (proposal.sure ? "" : ", not sure: " + proposal.why) +
                        "; Accept or Reject in the video view";
      });
}

void accept_video_proposal(WorkbenchState& state) {
  VideoState& video = state.video;
  if (!video.proposal) return;
  const SyncProposal proposal = *std::exchange(video.proposal, std::nullopt);
  for (size_t index = 0; index < video.videos.size(); ++index)
    if (video.videos[index].attachment.name == video.proposal_for)
      set_video_sync(state, index, proposal.offset, video.videos[index].attachment.rate,
                     "proposed offset accepted");
}

void reject_video_proposal(WorkbenchState& state) {
  if (!state.video.proposal) return;
  state.video.proposal.reset();
  state.notice = "video " + state.video.proposal_for + ": proposed offset rejected";
}

namespace {

// The one label selected, or a refusal on the status bar.
std::optional<Label> selected_label(WorkbenchState& state) {
  if (!state.document) return fail(state, "export clip: open a recording first"), std::nullopt;
  if (state.selection.labels.size() != 1)
    return fail(state, "export clip: select one label (click it in the lanes or the table)"),
           std::nullopt;
  for (const Label& label : state.document->labels)
    if (label.id == state.selection.labels.front()) return label;
  return fail(state, "export clip: the selected label is not in this recording"), std::nullopt;
}

}  // namespace

void ask_clip_file(WorkbenchState& state) {
  const std::optional<Label> label = selected_label(state);
  if (!label) return;
  const fs::path recording(state.document->path);
  state.file_browser.open(
      {BrowseMode::kSaveFile,
       "export clip",
       "Export clip",
       recording.parent_path().string(),
       {".mp4", ".mkv", ".mov", ".avi", ".webm"},
       recording.stem().string() + "-label-" + std::to_string(label->id) + ".mp4"});
}

void export_clip(WorkbenchState& state, const std::string& out) {
  const std::optional<Label> label = selected_label(state);
  if (!label) return;
  std::vector<std::string> words;
  try {
    words = {cluster::program_beside_this_one("tactile"),
             "clip",
             state.document->path,
             "--label",
             std::to_string(label->id),
             "--out",
             out};
  } catch (const Error& failure) {
    return void(fail(state, "export clip: " + std::string(failure.what())));
  }
  if (!state.document->labels_path.empty())
    words.insert(words.end(), {"--labels", state.document->labels_path});
  start_job<std::string>(
      state, "clip", "export clip of label " + std::to_string(label->id),
      [words, out](JobProgress&) {
        const cluster::ProgramOutput made = cluster::run_captured(words);
        if (made.exit_code != 0) throw Error(out, made.out);
        return out;
      },
      [](WorkbenchState& window, Job<std::string>& job) {
        if (std::optional<std::string> written = job_result(window, job))
          window.notice = "wrote clip " + *written;
      });
}

bool video_edit_is_newest(const WorkbenchState& state) {
  const VideoState& video = state.video;
  if (video.undo.empty()) return false;
  const LabelStore* store = state.document ? state.document->store.get() : nullptr;
  if (!store) return true;
  try {
    const std::vector<JournalEntry> next = store->next_undo(state.labelling.annotator);
    return next.empty() || next.front().sequence <= video.undo.back().journal;
  } catch (const Error&) {
    return true;
  }
}

bool undo_video_edit(WorkbenchState& state, bool redo) {
  VideoState& video = state.video;
  if (redo ? !(video.redo_is_video && !video.redo.empty()) : !video_edit_is_newest(state))
    return false;
  std::vector<VideoState::Edit>& from = redo ? video.redo : video.undo;
  std::vector<VideoState::Edit>& to = redo ? video.undo : video.redo;
  VideoState::Edit edit = std::move(from.back());
  from.pop_back();
  std::vector<VideoAttachment> now = attachments_of(video);
  try {
    write_attachments(video.recording, edit.before);
  } catch (const Error& failure) {
    from.push_back(std::move(edit));
    return fail(state, "video: " + std::string(failure.what()));
  }
  show(state, edit.before);
  to.push_back({std::move(now), journal_now(state), edit.what});
  video.redo_is_video = !redo || !video.redo.empty();
  state.error.clear();
  state.notice = (redo ? "redone: " : "undone: ") + edit.what;
  return true;
}

bool videos_caught_up(const WorkbenchState& state) {
  // Decoded, and drawn where it is drawn: the view uploads a frame the frame after the worker
  // has it.
  return std::all_of(state.video.videos.begin(), state.video.videos.end(),
                     [&](const VideoState::Shown& shown) {
                       if (!shown.player->caught_up()) return false;
                       const std::shared_ptr<const VideoFrame> frame = shown.player->shown();
                       return !frame || shown.drawn_at != state.frame ||
                              static_cast<double>(frame->index) == shown.texture.key;
                     });
}

}  // namespace tactile
