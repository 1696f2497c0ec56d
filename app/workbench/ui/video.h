#pragma once
// The videos attached to the open recording (docs/VIDEO.md): loaded with the recording, each
// shown by a VideoPlayer on its own worker at the time cursor, their offsets nudged, marked
// from two instants or proposed from the picture's motion (a job), every change written to
// RECORDING.videos.json at once and undoable with Ctrl+Z like a label edit.

#include <string>

#include "workbench_state.h"

namespace tactile {

// Once a frame: the attachments read again when another recording is open, and every player
// asked for the frame at the cursor.
void update_videos(WorkbenchState& state);
// Attaches a video file to the open recording (checked by opening it on the player's worker;
// a file that cannot be read is refused with the reason). False with state.error on failure.
bool attach_video(WorkbenchState& state, const std::string& path);
bool detach_video(WorkbenchState& state, size_t index);
// Moves the selected video's offset by `seconds` (later: the video shown later).
bool nudge_video(WorkbenchState& state, double seconds);
// The selected video's offset (and rate) set, as one undoable edit named `what`.
bool set_video_sync(WorkbenchState& state, size_t index, double offset, double rate,
                    const std::string& what);
// Moves the cursor to the selected video's previous or next frame.
void step_video_frame(WorkbenchState& state, int direction);
// Marks an instant where the video and the skin agree; after two, offset and rate from both.
void mark_video_instant(WorkbenchState& state);
// Proposes the selected video's offset from its motion and the skin's activity (a job).
void propose_video_offset(WorkbenchState& state);
void accept_video_proposal(WorkbenchState& state);
void reject_video_proposal(WorkbenchState& state);
// View > Export clip: asks where, for the selected label (one label selected, else refused).
void ask_clip_file(WorkbenchState& state);
// Encodes the clip of the selected label into `out` as a job (`tactile clip`, docs/VIDEO.md).
void export_clip(WorkbenchState& state, const std::string& out);
// Ctrl+Z / Ctrl+Shift+Z, when the newest edit is a video's: true when one was undone/redone.
bool undo_video_edit(WorkbenchState& state, bool redo);
// Whether the newest edit to undo is a video's (it is newer than the label store's).
bool video_edit_is_newest(const WorkbenchState& state);
// The selected video's frame interval (1/30 s until it is open).
double video_frame_seconds(const WorkbenchState& state);
// Every player shows the frame it was asked for (or cannot).
bool videos_caught_up(const WorkbenchState& state);
bool has_videos(const WorkbenchState& state);

}  // namespace tactile
