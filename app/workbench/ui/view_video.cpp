// Video view: the attached videos side by side, each at the frame the time cursor shows, with
// the selected one's synchronisation: nudges, two-instant marks, the proposed offset.
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "gl_texture.h"
#include "jobs.h"
#include "tactile/text.h"
#include "video.h"
#include "views.h"

namespace tactile {

namespace {

constexpr double kDragSecondsPerPixel = 0.01;  // a drag over a video nudges its offset

bool small_button(WorkbenchState& state, const char* label, const std::string& item,
                  const std::string& tip, bool enabled = true) {
  if (!enabled) ImGui::BeginDisabled();
  const bool pressed = ImGui::SmallButton(label);
  if (!enabled) ImGui::EndDisabled();
  remember_item(state, item, tip);
  ImGui::SameLine();
  return pressed && enabled;
}

void draw_controls(WorkbenchState& state) {
  VideoState& video = state.video;
  const double frame = video_frame_seconds(state);
  if (small_button(state, "Attach...", "button:video:attach", "Attach a video file (Video menu)"))
    state.file_browser.open({BrowseMode::kOpenFile,
                             "attach video",
                             "Attach video",
                             state.workspace,
                             {".mp4", ".mkv", ".mov", ".avi", ".webm"},
                             ""});
  const bool any = !video.videos.empty();
  if (small_button(state, "<<", "button:video:nudge-earlier",
                   "Show the selected video one frame earlier against the skin (Alt+Left)", any))
    nudge_video(state, -frame);
  if (small_button(state, ">>", "button:video:nudge-later",
                   "Show the selected video one frame later against the skin (Alt+Right)", any))
    nudge_video(state, frame);
  if (small_button(state, video.mark ? "Mark 2" : "Mark", "button:video:mark",
                   "Where the video and the skin show the same event: mark it (M); two marks set "
                   "offset and rate",
                   any))
    mark_video_instant(state);
  if (small_button(state, video.drawing_region ? "Drawing..." : "Region", "button:video:region",
                   "Draw, with a drag over the selected video, the part of the picture where its "
                   "motion is looked for (a hand near the skin, not people walking by)",
                   any))
    video.drawing_region = !video.drawing_region;
  if (video.region && small_button(state, "Whole picture", "button:video:whole",
                                   "Look for motion in the whole picture again"))
    video.region.reset();
  AnyJob* job = running_job(state, "video sync");
  if (small_button(state, "Propose offset", "button:video:propose",
                   "Correlate the video's motion with the skin's activity and propose an offset",
                   any && !job))
    propose_video_offset(state);
  if (small_button(state, "Detach", "button:video:detach",
                   "Detach the selected video (its file is kept; Ctrl+Z brings it back)", any))
    detach_video(state, video.selected);
  ImGui::NewLine();
  if (job) draw_job(state, job, nullptr, "proposing an offset");
  if (video.proposal) {
    const SyncProposal& proposal = *video.proposal;
    ImGui::TextColored(
        proposal.sure ? ImVec4(0.5f, 0.9f, 0.5f, 1.0f) : ImVec4(1.0f, 0.75f, 0.4f, 1.0f),
        "%s: offset %s s, confidence %s%s%s", video.proposal_for.c_str(),
        fixed_text(proposal.offset, 3).c_str(), fixed_text(proposal.confidence, 2).c_str(),
        proposal.sure ? "" : " - not sure: ", proposal.why.c_str());
    remember_item(state, "video:proposal");
    ImGui::SameLine();
    if (small_button(state, "Accept", "button:video:accept", "Take the proposed offset"))
      accept_video_proposal(state);
    if (small_button(state, "Reject", "button:video:reject", "Keep the offset as it is"))
      reject_video_proposal(state);
    ImGui::NewLine();
  }
}

// A frame fitted into `area` at `origin` (uploaded when `texture` holds another one): the
// picture's box on the screen, also kept as the box `name`.
ScreenRect draw_picture(WorkbenchState& state, VideoTexture& texture, const VideoFrame& frame,
                        double key, ImVec2 origin, ImVec2 area, const std::string& name) {
  if (key != texture.key || texture.id == 0) {
    const bool same = frame.width == texture.width && frame.height == texture.height;
    texture.id =
        upload_rgba_texture(texture.id, frame.width, frame.height, frame.rgba.data(), same);
    texture.key = key;
    texture.width = frame.width;
    texture.height = frame.height;
  }
  const float scale =
      std::min(area.x / static_cast<float>(frame.width), area.y / static_cast<float>(frame.height));
  const ImVec2 picture(frame.width * scale, frame.height * scale);
  const ImVec2 at(origin.x + 0.5f * (area.x - picture.x), origin.y + 0.5f * (area.y - picture.y));
  const ImVec2 end(at.x + picture.x, at.y + picture.y);
  ImGui::GetWindowDrawList()->AddImage(
      reinterpret_cast<ImTextureID>(static_cast<intptr_t>(texture.id)), at, end);
  remember_box(state, name, at, end);
  return to_rect(at, end);
}

// Words over a picture: why it is not (or not newly) shown.
void draw_words_over(WorkbenchState& state, ImVec2 origin, float width, const std::string& words,
                     const std::string& item) {
  if (words.empty()) return;
  ImGui::SetCursorScreenPos(ImVec2(origin.x + 6.0f, origin.y + 6.0f));
  ImGui::PushTextWrapPos(origin.x + width - 6.0f);
  ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.45f, 1.0f), "%s", words.c_str());
  ImGui::PopTextWrapPos();
  remember_item(state, item);
}

// A point of the screen as fractions of a picture's box, clamped to it.
ImVec2 fraction_in(const ScreenRect& box, ImVec2 point) {
  return ImVec2(std::clamp((point.x - box.x0) / std::max(1.0f, box.width()), 0.0f, 1.0f),
                std::clamp((point.y - box.y0) / std::max(1.0f, box.height()), 0.0f, 1.0f));
}

// What a drag over a picture did, for the caller to write once the videos are drawn.
struct PictureDrag {
  std::optional<double> offset;       // nudged to
  std::optional<VideoRegion> region;  // drawn
};

// The picture of one video in `size`, with its caption above.
PictureDrag draw_one(WorkbenchState& state, size_t index, ImVec2 size) {
  PictureDrag done;
  VideoState& video = state.video;
  VideoState::Shown& shown = video.videos[index];
  const VideoAttachment& attachment = shown.attachment;
  const std::shared_ptr<const VideoFrame> frame = shown.player->shown();
  const std::shared_ptr<const VideoInfo> info = shown.player->info();
  const double video_time = attachment.video_time(state.clock.time());
  const bool is_selected = index == video.selected;
  shown.drawn_at = state.frame;
  ImGui::PushID(static_cast<int>(index));
  ImGui::BeginGroup();
  const ImVec4 caption_colour =
      is_selected ? ImVec4(1.0f, 0.85f, 0.45f, 1.0f) : ImVec4(0.75f, 0.75f, 0.75f, 1.0f);
  std::string caption = attachment.name + "  offset " + fixed_text(attachment.offset, 3) + " s";
  if (attachment.rate != 1.0) caption += " x" + significant_text(attachment.rate, 7);
  if (attachment.offset < 0.0)
    caption += " (starts " + fixed_text(-attachment.offset, 1) + " s before the recording)";
  if (frame)
    caption +=
        "  frame " + std::to_string(frame->index) + " at " + fixed_text(frame->time, 3) + " s";
  ImGui::TextColored(caption_colour, "%s", caption.c_str());
  remember_item(state, "video:caption:" + attachment.name);
  const float caption_height = ImGui::GetFrameHeightWithSpacing();
  const ImVec2 area(size.x, std::max(20.0f, size.y - caption_height));
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 end(origin.x + area.x, origin.y + area.y);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, end, IM_COL32(12, 12, 14, 255));
  std::optional<ScreenRect> picture;
  if (frame && frame->width > 0)
    picture = draw_picture(state, shown.texture, *frame, static_cast<double>(frame->index), origin,
                           area, "video:picture:" + attachment.name);
  ImGui::SetCursorScreenPos(origin);
  ImGui::InvisibleButton("picture", area);
  remember_item(state, "video:" + attachment.name,
                "Click to choose this video for the keys; drag sideways to nudge its offset "
                "(after Region: drag to draw where the motion is looked for)");
  const bool drawing = video.drawing_region && is_selected && picture;
  if (ImGui::IsItemActivated()) video.selected = index;
  if (drawing && ImGui::IsItemActive()) {
    const ImVec2 from = ImGui::GetIO().MouseClickedPos[0], to = ImGui::GetIO().MousePos;
    draw->AddRect(ImVec2(std::min(from.x, to.x), std::min(from.y, to.y)),
                  ImVec2(std::max(from.x, to.x), std::max(from.y, to.y)),
                  IM_COL32(255, 215, 110, 255), 0.0f, 0, 2.0f);
  } else if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 2.0f)) {
    // The picture follows the drag; the offset is written as one edit on release.
    if (!video.drag_from) video.drag_from = attachment.offset;
    shown.attachment.offset += ImGui::GetIO().MouseDelta.x * kDragSecondsPerPixel;
  }
  if (ImGui::IsItemDeactivated() && drawing) {
    const ImVec2 a = fraction_in(*picture, ImGui::GetIO().MouseClickedPos[0]);
    const ImVec2 b = fraction_in(*picture, ImGui::GetIO().MousePos);
    done.region = VideoRegion{std::min(a.x, b.x), std::min(a.y, b.y), std::abs(b.x - a.x),
                              std::abs(b.y - a.y)};
  } else if (ImGui::IsItemDeactivated() && video.drag_from) {
    done.offset = shown.attachment.offset;
    shown.attachment.offset = *std::exchange(video.drag_from, std::nullopt);
  }
  // The region the proposal looks in, over the video it was drawn on.
  if (picture && video.region && video.region_for == attachment.name) {
    const VideoRegion& region = *video.region;
    const ScreenRect& box = *picture;
    const ImVec2 low(box.x0 + static_cast<float>(region.x) * box.width(),
                     box.y0 + static_cast<float>(region.y) * box.height());
    const ImVec2 high(low.x + static_cast<float>(region.width) * box.width(),
                      low.y + static_cast<float>(region.height) * box.height());
    draw->AddRect(low, high, IM_COL32(255, 215, 110, 220), 0.0f, 0, 1.5f);
    remember_box(state, "video:region:" + attachment.name, low, high);
  }
  std::string words = shown.player->problem();
  if (words.empty() && shown.player->opening()) words = "opening " + shown.path + "...";
  if (words.empty() && info) words = video_time_problem(*info, video_time, attachment.offset);
  draw_words_over(state, origin, area.x, words, "video:problem:" + attachment.name);
  if (is_selected && video.videos.size() > 1)
    draw->AddRect(origin, end, IM_COL32(255, 215, 110, 200), 0.0f, 0, 2.0f);
  ImGui::SetCursorScreenPos(ImVec2(origin.x, end.y));
  ImGui::EndGroup();
  ImGui::PopID();
  return done;
}

// The live camera's newest frame, stamped on the stream's clock.
void draw_camera(WorkbenchState& state, LiveState::CameraShown& camera, ImVec2 size) {
  std::string caption = "camera " + camera.url;
  if (camera.frame)
    caption += "  at " + fixed_text(camera.frame->time, 3) + " s, " +
               std::to_string(camera.received) + " frames";
  if (!camera.recording.empty()) caption += "  recording";
  ImGui::TextColored(ImVec4(0.75f, 0.75f, 0.75f, 1.0f), "%s", caption.c_str());
  remember_item(state, "video:caption:camera");
  const ImVec2 area(size.x, std::max(20.0f, ImGui::GetContentRegionAvail().y));
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::GetWindowDrawList()->AddRectFilled(origin, ImVec2(origin.x + area.x, origin.y + area.y),
                                            IM_COL32(12, 12, 14, 255));
  if (camera.frame && camera.frame->width > 0)
    draw_picture(state, camera.texture, *camera.frame, camera.frame->time, origin, area,
                 "video:picture:camera");
  draw_words_over(state, origin, area.x, camera.error, "video:problem:camera");
  ImGui::SetCursorScreenPos(origin);
  ImGui::Dummy(area);
}

}  // namespace

void draw_video_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("video_view", size, false,
                    ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  if (state.live.connected && (state.live.camera || state.video.videos.empty())) {
    if (state.live.camera)
      draw_camera(state, *state.live.camera, ImGui::GetContentRegionAvail());
    else
      ImGui::TextDisabled("No camera: --camera URL beside --connect (docs/VIDEO.md).");
    ImGui::EndChild();
    return;
  }
  VideoState& video = state.video;
  if (state.options.only_view != "clip") draw_controls(state);
  if (!video.problem.empty())
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", video.problem.c_str());
  if (video.videos.empty()) {
    ImGui::TextDisabled("No video attached to this recording: Attach... (docs/VIDEO.md).");
    ImGui::EndChild();
    return;
  }
  const ImVec2 room = ImGui::GetContentRegionAvail();
  // A clip of one video (`tactile clip --video NAME`) shows that one alone.
  const std::string& only = state.options.clip_video;
  std::vector<size_t> drawn;
  for (size_t index = 0; index < video.videos.size(); ++index)
    if (only.empty() || video.videos[index].attachment.name == only) drawn.push_back(index);
  const size_t count = std::max<size_t>(1, drawn.size());
  const float gap = 6.0f;
  const float width = (room.x - gap * static_cast<float>(count - 1)) / static_cast<float>(count);
  std::optional<std::pair<size_t, PictureDrag>> dragged;
  for (size_t index : drawn) {
    if (index != drawn.front()) ImGui::SameLine(0.0f, gap);
    PictureDrag done = draw_one(state, index, ImVec2(std::max(20.0f, width), room.y));
    if (done.offset || done.region) dragged = {index, done};
  }
  ImGui::EndChild();
  if (dragged) {
    const auto& [index, done] = *dragged;
    const VideoAttachment& attachment = video.videos[index].attachment;
    if (done.offset)
      set_video_sync(state, index, *done.offset, attachment.rate,
                     "dragged " + seconds_text(*done.offset - attachment.offset) + " s");
    if (done.region) {
      video.region = *done.region;
      video.region_for = attachment.name;
      video.drawing_region = false;
      video.proposal.reset();
      state.notice = "video " + attachment.name + ": its motion is looked for in the region drawn";
    }
  }
}

// A label as a talk shows it: the skin and the video side by side, under them the signals with
// the cursor and the lanes (`tactile clip`).
void draw_clip_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("clip_view", size, false,
                    ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  const float spacing = ImGui::GetStyle().ItemSpacing.y;
  const float top = std::floor(size.y * 0.55f);
  const float signals = std::floor(size.y * 0.25f);
  const float lanes = size.y - top - signals - 2 * spacing;
  const float half = std::floor(size.x * 0.5f);
  draw_skin_panel_view(state, ImVec2(half - 4.0f, top));
  ImGui::SameLine(0.0f, 8.0f);
  draw_video_view(state, ImVec2(size.x - half - 4.0f, top));
  draw_signals_view(state, ImVec2(size.x, signals));
  draw_timeline_view(state, ImVec2(size.x, lanes));
  ImGui::EndChild();
}

}  // namespace tactile
