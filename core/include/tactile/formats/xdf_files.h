#pragma once
// XDF recordings (Lab Streaming Layer's LabRecorder) read into recordings: one numeric
// stream becomes the recording's samples, resampled onto its nominal rate with gaps kept as
// gaps, and one markers stream becomes ground-truth labels (docs/IMPORT.md, "XDF").
//
// libxdf does the reading, but it trusts every length and count a file declares and reads
// past the buffers it allocates. So the file is walked here first (every chunk within the
// file, every sample chunk's content exactly what its stream's header declares, the XML
// headers parsed, counts bounded), and libxdf reads a canonical copy holding only the two
// chosen streams (scan_xdf and import_xdf say how). Bad input is refused with
// tactile::Error naming the file, the chunk and its byte offset, or the stream.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tactile/formats/csv_files.h"
#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

struct XdfImportOptions {
  // --stream: the data stream by NAME, or "type:TYPE". "": the only numeric stream with a
  // nominal rate.
  std::string stream;
  // --markers: the markers stream (channel format string) by NAME or "type:TYPE". "": the
  // only markers stream; a file without one gives no labels.
  std::string markers;
};

// The most channels a stream may declare, and the largest XML chunk read.
inline constexpr int64_t kMaxXdfChannels = 65536;
inline constexpr uint64_t kMaxXdfXmlBytes = uint64_t{64} << 20;
// A nominal rate above this is refused (libxdf turns rates into int).
inline constexpr double kMaxXdfRate = 1.0e6;

// One stream as the file declares it.
struct XdfStreamInfo {
  uint32_t id = 0;
  std::string name, type;
  std::string format;  // int8, int16, int32, int64, float32, double64 or string
  int64_t channels = 0;
  double rate_hz = 0.0;  // nominal; 0: irregular (markers)
  int64_t samples = 0;   // in all its sample chunks
  // (collection time, offset value), in the file's order (a clock reset sends the collection
  // times back: clock_corrected_stamps splits them there).
  std::vector<std::pair<double, double>> clock_offsets;
  // Where its sample chunks are: byte offset and size of each whole chunk.
  std::vector<std::pair<uint64_t, uint64_t>> sample_chunks;
};

// Walks every chunk of the file and checks it (see above); the streams in the order their
// headers appear. Throws tactile::Error naming the file, the chunk and its byte offset.
std::vector<XdfStreamInfo> scan_xdf(const std::string& path);

// "NAME (type TYPE, C channels, R Hz, N samples)" for each, one per line with an indent:
// what a refusal that asks to choose lists.
std::string xdf_stream_list(const std::vector<XdfStreamInfo>& streams);

// A marker: its time (clock-corrected, seconds from the data stream's first stamp) and text.
struct XdfMarker {
  double time = 0.0;
  std::string text;
};

// Markers paired into labels [t0, t1) on region "all", annotator "import", ground truth:
//   "CLASS start" / "CLASS begin" opens CLASS until "CLASS end" (case-insensitive words);
//   "CLASS" opens CLASS until the next marker, whatever it is;
//   "none" or "" opens nothing (it only closes the label before).
// A plain marker or another start while a "start" label is open, and an "end" that closes
// nothing, are refused naming the markers. An unclosed plain label ends at `end_time`, an
// unclosed "start" is refused. Labels are clipped to the data [0, end_time); one that then
// holds less than one sample (`sample_seconds`: a marker at the data's end, two markers at one
// instant, one before the data) is no label: it is dropped and said in `dropped` ("marker 7
// "stop" at 0.8999999999999986 s: ..."). `where` names the stream in refusals.
struct XdfMarkerLabels {
  std::vector<Label> labels;
  std::vector<std::string> dropped;
};
XdfMarkerLabels labels_from_markers(const std::vector<XdfMarker>& markers, double end_time,
                                    double sample_seconds, const std::string& where);

// The time stamps' clock correction as XDF's ClockOffset chunks say: a stamp t gets the
// offset measured around it added, interpolated linearly between the two measurements whose
// collection times enclose t, the first (last) measurement's before (after) them.
double clock_corrected(double stamp, const std::vector<std::pair<double, double>>& offsets);

// A device's clock reset mid-recording (a restart, a clock set) sends its stamps back (or
// forward) by hours at one sample, and the offsets measured after it differ by as much: one
// interpolation across the reset is nonsense. As pyxdf's handle_clock_resets finds them, a
// reset lies between two successive measurements (in the file's order) whose collection time
// goes back, or forward more than kXdfResetSeconds beyond the usual interval (the median), and
// whose offset changes more than kXdfResetOffsetSeconds beyond the usual change. Returns the
// index of the first measurement after each reset; none with fewer than 3 measurements.
inline constexpr double kXdfResetSeconds = 5.0;
inline constexpr double kXdfResetOffsetSeconds = 1.0;
std::vector<size_t> xdf_clock_resets(const std::vector<std::pair<double, double>>& offsets);

// A stream's stamps (in the file's order) on the recorder's clock: the offsets (in the file's
// order) split at the resets into segments, each sample corrected (clock_corrected) by the
// segment it was sent in. The samples move on to the next segment at the sample whose stamp
// jumps as the offsets did (by about minus the offset's jump), or at the first that lies nearer
// the next segment's measurements than the current one's; never back.
std::vector<double> clock_corrected_stamps(const std::vector<double>& stamps,
                                           const std::vector<std::pair<double, double>>& offsets);

// Samples with irregular stamps (rows: samples, non-decreasing stamps) onto a grid from the
// first stamp at 1/rate_hz: each grid point takes the linear interpolation of the two
// samples around it when they are at most 1.5/rate_hz apart, and is a gap (NaN) when they
// are further apart, so a dropout stays a gap. A grid point on a sample takes its value.
// `where` names the stream in refusals (stamps going back, a grid too large).
SampleMatrix resample_to_rate(const std::vector<double>& stamps, const SampleMatrix& samples,
                              double rate_hz, const std::string& where);

// The chosen data stream as a recording of the layout (channel count must be the layout's)
// and the chosen markers stream's labels; times from the data stream's first stamp.
ImportedRecording import_xdf(const std::string& path, const SkinLayout& layout,
                             const XdfImportOptions& options);

}  // namespace tactile
