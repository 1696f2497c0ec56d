#!/bin/sh
# The window's frames while a 1080p video plays in the video view (bench/VIDEO.md): the headless
# workbench plays a simulated flux recording for 10 s (600 frames), once without a video and once
# with a long 1080p H.264 file attached; the median and longest frame-building times of the 600
# frames of each run (the state's `since_last_state`: opening is left out).
# Usage: bench/video_view.sh [BUILD_DIR] [VIDEO] (VIDEO: bench/video_seek.sh's file by default).
set -e
build=${1:-build}
video=${2:-/tmp/tactile-video-seek-1080p-1800s.mp4}
[ -s "$video" ] || { echo "no $video: run bench/video_seek.sh first" >&2; exit 2; }
folder=$(mktemp -d)
trap 'rm -rf "$folder"' EXIT
"$build/bin/tactile" simulate --skin flux --subjects 1 --repetitions 1 --out "$folder/flux" >/dev/null
recording=$(ls "$folder"/flux/*.h5)
run() {
  printf 'wait 5\nwait video\nstate %s\nplay 10\nstate %s\n' "$folder/$1-opened.json" \
    "$folder/$1.json" > "$folder/$1.txt"
  "$build/bin/tactile-workbench-headless" "$recording" --size 1600x900 \
    --settings "$folder/settings.json" --script "$folder/$1.txt" >/dev/null
}
run idle
"$build/bin/tactile" video attach "$recording" "$video" --name long >/dev/null 2>&1
run video
python3 - "$folder" <<'PY'
import json, sys
folder = sys.argv[1]
idle = json.load(open(folder + "/idle.json"))
video = json.load(open(folder + "/video.json"))
idle_frames, video_frames = idle["since_last_state"], video["since_last_state"]
print("run      frames median   longest")
for name, run in (("idle", idle_frames), ("video", video_frames)):
    print(f"{name:6} {run['frames']:8d} {1000 * run['median_frame_seconds']:6.2f} ms"
          f" {1000 * run['longest_frame_seconds']:7.2f} ms")
frame = video["videos"]["list"][0]
print(f"video shown: frame {frame['frame']} (wanted {frame['wanted_frame']}), "
      f"{frame['width']}x{frame['height']} {frame['codec']}")
print(f"longest frame playing the video / idle median: "
      f"{video_frames['longest_frame_seconds'] / idle_frames['median_frame_seconds']:.1f}x; "
      f"longest idle / idle median: "
      f"{idle_frames['longest_frame_seconds'] / idle_frames['median_frame_seconds']:.1f}x; "
      f"median with / without: "
      f"{video_frames['median_frame_seconds'] / idle_frames['median_frame_seconds']:.2f}x")
PY
