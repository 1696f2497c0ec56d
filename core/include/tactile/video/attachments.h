#pragma once
// Videos attached to a recording: each with a name, its file, the recording time at which the
// video's first frame is shown (offset) and a rate correction. They are kept beside the
// recording in RECORDING.videos.json (docs/VIDEO.md), written whole and atomically; a path
// inside the recording's folder is kept relative to it, so the folder can move.

#include <optional>
#include <string>
#include <vector>

namespace tactile {

struct VideoAttachment {
  std::string name;   // unique within the recording: "front", "camera-2"
  std::string path;   // as kept: relative to the recording's folder when inside it
  double offset = 0;  // recording time (s) at which the video's time 0 is shown; may be < 0
  double rate = 1;    // video seconds per recording second (1: the clocks agree)

  double video_time(double recording_time) const { return (recording_time - offset) * rate; }
  double recording_time(double video_time) const { return offset + video_time / rate; }
};

// RECORDING.videos.json for RECORDING.
std::string attachments_path(const std::string& recording_path);
// The recording's attachments; none when the file is absent. Throws tactile::Error naming the
// file (and the entry) when it is malformed.
std::vector<VideoAttachment> read_attachments(const std::string& recording_path);
// Writes them all (the file removed when there are none).
void write_attachments(const std::string& recording_path,
                       const std::vector<VideoAttachment>& attachments);
// The video file's path as opened: `attachment.path` resolved against the recording's folder.
std::string video_path(const std::string& recording_path, const VideoAttachment& attachment);
// The path to keep for `video` (relative when inside the recording's folder, else absolute).
std::string kept_video_path(const std::string& recording_path, const std::string& video);
// Offset and rate from two instants seen in both: recording times r1, r2 and the video times
// v1, v2 of the same events. Throws tactile::Error when r1 == r2 or the rate is not positive.
void sync_from_two_points(VideoAttachment& attachment, double r1, double v1, double r2, double v2);
// The attachment named `name`, or nullptr.
const VideoAttachment* find_attachment(const std::vector<VideoAttachment>& attachments,
                                       const std::string& name);
// Whether `name` may name an attachment: letters, digits, '-', '_' and '.' only, not empty.
bool valid_attachment_name(const std::string& name);
// The index of the attachment named `name`; throws tactile::Error naming the recording and the
// names attached when there is none.
size_t attachment_index(const std::vector<VideoAttachment>& attachments, const std::string& name,
                        const std::string& recording_path);
// A name not yet taken: the video file's stem, then "stem-2", ...
std::string free_attachment_name(const std::vector<VideoAttachment>& attachments,
                                 const std::string& video);

}  // namespace tactile
