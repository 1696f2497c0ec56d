#!/bin/sh
# The video seek benchmark (bench/VIDEO.md): makes a 30-minute 1080p 30 fps H.264 file with the
# ffmpeg program (only benchmarks use it) unless a video is given, then runs video_seek_bench.
# Usage: bench/video_seek.sh [BUILD_DIR] [VIDEO]; VIDEO_SECONDS=300 makes a shorter file (the
# random reads and play do not depend on the length; the index pass grows with it).
set -e
build=${1:-build}
seconds=${VIDEO_SECONDS:-1800}
video=${2:-/tmp/tactile-video-seek-1080p-${seconds}s.mp4}
if [ ! -s "$video" ]; then
  ffmpeg -hide_banner -loglevel error -y -f lavfi -i testsrc2=size=1920x1080:rate=30 -t "$seconds" \
    -c:v libx264 -preset ultrafast -g 60 -pix_fmt yuv420p "$video.part.mp4"
  mv "$video.part.mp4" "$video"
fi
exec "$build/bench/video_seek_bench" "$video"
