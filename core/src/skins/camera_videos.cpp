#include <filesystem>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/sim/touch_video.h"
#include "tactile/skins/workspace.h"
#include "tactile/video/attachments.h"

namespace tactile {

namespace fs = std::filesystem;

std::vector<std::string> write_camera_videos(const std::vector<std::string>& files, uint64_t seed,
                                             const SimulationProgress& progress) {
  std::vector<std::string> written;
  for (size_t item = 0; item < files.size(); ++item) {
    const std::string& recording = files[item];
    const RecordingFile file(recording);
    if (file.streams().empty()) throw Error(recording, "no stream to film");
    const StreamInfo& stream = file.streams().front();
    const fs::path database = fs::path(recording).parent_path() / "labels.db";
    LabelFilter filter;
    filter.recording = file.recording_id();
    filter.source = LabelSource::kGroundTruth;
    const std::vector<Label> touches =
        LabelStore(database.string(), LabelStore::OpenMode::kExisting).list(filter);
    TouchVideoOptions options;
    options.offset = stream.start_time;
    options.duration = stream.duration();
    options.seed = seed + item;
    const std::string video =
        (fs::path(recording).parent_path() / (file.recording_id() + "-camera.mp4")).string();
    write_touch_video(video, load_layout(file.layout_id()), touches, options);
    std::vector<VideoAttachment> attachments = read_attachments(recording);
    std::erase_if(attachments, [](const VideoAttachment& a) { return a.name == "camera"; });
    VideoAttachment camera;
    camera.name = "camera";
    camera.path = kept_video_path(recording, video);
    camera.offset = stream.start_time;
    attachments.push_back(camera);
    write_attachments(recording, attachments);
    written.push_back(video);
    if (progress) progress(static_cast<int>(item + 1), static_cast<int>(files.size()));
  }
  return written;
}

}  // namespace tactile
