#include "tactile/formats/xdf_files.h"

#include <tinyxml2.h>
#include <unistd.h>
#include <xdf.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <streambuf>

#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile {

namespace {

//---- Reading bytes ---------------------------------------------------------------------------

// The file's bytes at an offset, read with the file's size known: a read past the end is
// refused, never made.
class XdfBytes {
 public:
  explicit XdfBytes(const std::string& path) : path_(path) {
    std::error_code error;
    size_ = std::filesystem::file_size(path, error);
    if (error) throw Error(path, "cannot read: " + error.message());
    file_.open(path, std::ios::binary);
    if (!file_) throw Error(path, "cannot open");
  }
  uint64_t size() const { return size_; }
  const std::string& path() const { return path_; }
  void read(uint64_t offset, void* out, uint64_t count, const std::string& where) {
    if (offset > size_ || count > size_ - offset)
      throw Error(where, "needs " + std::to_string(count) + " bytes at byte " +
                             std::to_string(offset) + ", the file ends at byte " +
                             std::to_string(size_));
    file_.seekg(static_cast<std::streamoff>(offset));
    file_.read(static_cast<char*>(out), static_cast<std::streamsize>(count));
    if (!file_) throw Error(where, "read failed at byte " + std::to_string(offset));
  }

 private:
  std::string path_;
  uint64_t size_ = 0;
  std::ifstream file_;
};

// A chunk's content held in memory (its size checked against the file first).
struct XdfCursor {
  const std::vector<uint8_t>& bytes;
  size_t at = 0;
  size_t left() const { return bytes.size() - at; }
};

template <typename T>
T xdf_take(XdfCursor& cursor, const std::string& where, const char* what) {
  if (cursor.left() < sizeof(T))
    throw Error(where, std::string("ends inside ") + what + " (" + std::to_string(cursor.left()) +
                           " bytes left, " + std::to_string(sizeof(T)) + " needed)");
  T value;
  std::memcpy(&value, cursor.bytes.data() + cursor.at, sizeof(T));  // XDF is little-endian
  cursor.at += sizeof(T);
  return value;
}

// XDF's variable-length integer: a byte 1, 4 or 8, then that many bytes.
uint64_t xdf_take_length(XdfCursor& cursor, const std::string& where, const char* what) {
  const auto width = xdf_take<uint8_t>(cursor, where, what);
  if (width == 1) return xdf_take<uint8_t>(cursor, where, what);
  if (width == 4) return xdf_take<uint32_t>(cursor, where, what);
  if (width == 8) return xdf_take<uint64_t>(cursor, where, what);
  throw Error(where, std::string(what) + ": length width " + std::to_string(width) +
                         " (XDF allows 1, 4 or 8)");
}

int64_t xdf_value_bytes(const std::string& format) {
  if (format == "int8") return 1;
  if (format == "int16") return 2;
  if (format == "int32" || format == "float32") return 4;
  if (format == "int64" || format == "double64") return 8;
  return 0;  // string, or unknown
}

//---- The walk -----------------------------------------------------------------------------

std::string xdf_child_text(const tinyxml2::XMLElement* info, const char* name) {
  const tinyxml2::XMLElement* child = info->FirstChildElement(name);
  const char* text = child ? child->GetText() : nullptr;
  return text ? std::string(text) : std::string();
}

std::string xdf_trimmed(const std::string& text) {
  size_t first = 0, last = text.size();
  while (first < last && std::isspace(static_cast<unsigned char>(text[first]))) ++first;
  while (last > first && std::isspace(static_cast<unsigned char>(text[last - 1]))) --last;
  return text.substr(first, last - first);
}

// A stream header's <info>: name, type, channel_count, nominal_srate, channel_format.
void xdf_read_header(const std::string& xml, XdfStreamInfo& stream, const std::string& where) {
  tinyxml2::XMLDocument document;
  if (document.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS)
    throw Error(where, std::string("stream header is not XML: ") + document.ErrorStr());
  const tinyxml2::XMLElement* info = document.FirstChildElement("info");
  if (!info) throw Error(where, "stream header has no <info>");
  stream.name = xdf_trimmed(xdf_child_text(info, "name"));
  stream.type = xdf_trimmed(xdf_child_text(info, "type"));
  stream.format = xdf_trimmed(xdf_child_text(info, "channel_format"));
  const std::string count = xdf_trimmed(xdf_child_text(info, "channel_count"));
  const std::string rate = xdf_trimmed(xdf_child_text(info, "nominal_srate"));
  char* end = nullptr;
  errno = 0;
  const long long channels = std::strtoll(count.c_str(), &end, 10);
  if (count.empty() || *end != '\0' || errno != 0 || channels < 1 || channels > kMaxXdfChannels)
    throw Error(where, "channel_count '" + printable_text(count) + "': a whole number from 1 to " +
                           std::to_string(kMaxXdfChannels) + " is needed");
  stream.channels = channels;
  const double nominal = rate.empty() ? 0.0 : std::strtod(rate.c_str(), &end);
  if ((!rate.empty() && *end != '\0') || !std::isfinite(nominal) || nominal < 0.0 ||
      nominal > kMaxXdfRate)
    throw Error(where, "nominal_srate '" + printable_text(rate) + "': a rate from 0 to " +
                           shortest_text(kMaxXdfRate) + " Hz is needed");
  stream.rate_hz = nominal;
  if (stream.format != "string" && xdf_value_bytes(stream.format) == 0)
    throw Error(where, "channel_format '" + printable_text(stream.format) +
                           "' (XDF has int8, int16, int32, int64, float32, double64, string)");
  // libxdf 0.99.8 reads one string per sample whatever the channel count, and would lose its
  // place in the file on a multi-channel string stream.
  if (stream.format == "string" && stream.channels != 1)
    throw Error(where, "a string stream of " + std::to_string(stream.channels) +
                           " channels (markers streams have one)");
}

// A Samples chunk's content after the stream id: every sample's stamp flag and values
// exactly fill it. Returns the number of samples.
uint64_t xdf_check_samples(XdfCursor& cursor, const XdfStreamInfo& stream,
                           const std::string& where) {
  const uint64_t count = xdf_take_length(cursor, where, "the sample count");
  // Each sample holds at least its stamp flag and one byte: a count the chunk cannot hold
  // is refused before walking it.
  if (count > cursor.left() / 2)
    throw Error(where, std::to_string(count) + " samples declared in " +
                           std::to_string(cursor.left()) + " bytes");
  const int64_t value_bytes = xdf_value_bytes(stream.format);
  for (uint64_t sample = 0; sample < count; ++sample) {
    const std::string place = where + " sample " + std::to_string(sample);
    const auto stamp_bytes = xdf_take<uint8_t>(cursor, place, "the time stamp flag");
    if (stamp_bytes != 0 && stamp_bytes != 8)
      throw Error(place, "time stamp of " + std::to_string(stamp_bytes) + " bytes (0 or 8)");
    if (stamp_bytes == 8) {
      const auto stamp = xdf_take<double>(cursor, place, "the time stamp");
      if (!std::isfinite(stamp)) throw Error(place, "time stamp is not a finite number");
    }
    if (value_bytes > 0) {
      const uint64_t need = static_cast<uint64_t>(value_bytes * stream.channels);
      if (cursor.left() < need)
        throw Error(place, "ends inside its values (" + std::to_string(cursor.left()) +
                               " bytes left, " + std::to_string(need) + " for " +
                               std::to_string(stream.channels) + " " + stream.format + ")");
      cursor.at += need;
    } else {
      const uint64_t length = xdf_take_length(cursor, place, "the string");
      if (length > cursor.left())
        throw Error(place, "string of " + std::to_string(length) + " bytes, " +
                               std::to_string(cursor.left()) + " left in the chunk");
      cursor.at += length;
    }
  }
  // libxdf reads a chunk sample by sample and never skips to its end: bytes left over would
  // be read as the next chunk.
  if (cursor.left() != 0)
    throw Error(where, std::to_string(cursor.left()) + " bytes after its " + std::to_string(count) +
                           " samples");
  return count;
}

//---- libxdf's printing ---------------------------------------------------------------------

// libxdf prints progress ("it took N clicks") to std::cout on every load. std::cout gets,
// once, a forwarding buffer that drops what the thread loading an XDF file writes while it
// loads: other threads' output passes untouched, and nothing is swapped per load (swapping
// std::cout's buffer or fd 1 around each call would race with every other writer).
thread_local bool xdf_muted = false;

class XdfMutedBuffer : public std::streambuf {
 public:
  explicit XdfMutedBuffer(std::streambuf* target) : target_(target) {}

 protected:
  int overflow(int c) override {
    if (xdf_muted || traits_type::eq_int_type(c, traits_type::eof()))
      return traits_type::not_eof(c);
    return target_->sputc(traits_type::to_char_type(c));
  }
  std::streamsize xsputn(const char* text, std::streamsize count) override {
    return xdf_muted ? count : target_->sputn(text, count);
  }
  int sync() override { return xdf_muted ? 0 : target_->pubsync(); }

 private:
  std::streambuf* target_;
};

struct XdfMuteScope {
  XdfMuteScope() {
    // Installed at the first load (a thread-safe static); kept for the program's life.
    static XdfMutedBuffer* const buffer = [] {
      auto* installed = new XdfMutedBuffer(std::cout.rdbuf());
      std::cout.rdbuf(installed);
      return installed;
    }();
    (void)buffer;
    xdf_muted = true;
  }
  ~XdfMuteScope() { xdf_muted = false; }
};

//---- The canonical copy libxdf reads ---------------------------------------------------------

void xdf_put_chunk(std::ofstream& out, uint16_t tag, const std::string& content) {
  const uint8_t width = 8;
  const uint64_t length = content.size() + 2;
  out.write(reinterpret_cast<const char*>(&width), 1);
  out.write(reinterpret_cast<const char*>(&length), 8);
  out.write(reinterpret_cast<const char*>(&tag), 2);
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
}

// A stream header libxdf parses to what was checked here. Ends in a NUL byte: libxdf makes a
// std::string of the chunk's buffer with strlen, which would read past a buffer without one.
std::string xdf_canonical_header(const XdfStreamInfo& stream) {
  char rate[64];
  std::snprintf(rate, sizeof rate, "%.17g", stream.rate_hz);
  std::string content(4, '\0');
  std::memcpy(content.data(), &stream.id, 4);
  content += "<?xml version=\"1.0\"?><info><name>s</name><type>t</type><channel_count>" +
             std::to_string(stream.channels) + "</channel_count><nominal_srate>" + rate +
             "</nominal_srate><channel_format>" + stream.format + "</channel_format></info>";
  content.push_back('\0');
  return content;
}

// A file of this process removed when done, in TMPDIR (or /tmp).
struct XdfTemporaryFile {
  std::string path;
  XdfTemporaryFile() {
    static std::atomic<uint64_t> counter{0};
    path = (std::filesystem::temp_directory_path() / ("tactile-xdf-" + std::to_string(::getpid()) +
                                                      "-" + std::to_string(++counter) + ".xdf"))
               .string();
  }
  ~XdfTemporaryFile() {
    std::error_code error;
    std::filesystem::remove(path, error);
  }
};

// The copy: magic, the chosen streams' headers (canonical), their sample chunks as they are
// (checked by scan_xdf), and a zero-length chunk that ends libxdf's loop. Clock offsets are
// left out (applied here, not by libxdf), as are footers, boundaries and other streams.
void xdf_write_copy(XdfBytes& bytes, const std::vector<const XdfStreamInfo*>& streams,
                    const std::string& out_path) {
  std::ofstream out(out_path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error(out_path, "cannot write the copy libxdf reads");
  out.write("XDF:", 4);
  for (const XdfStreamInfo* stream : streams) xdf_put_chunk(out, 2, xdf_canonical_header(*stream));
  // The chunks in file order, so each stream's samples stay in order.
  std::vector<std::pair<uint64_t, uint64_t>> chunks;
  for (const XdfStreamInfo* stream : streams)
    chunks.insert(chunks.end(), stream->sample_chunks.begin(), stream->sample_chunks.end());
  std::sort(chunks.begin(), chunks.end());
  std::vector<char> buffer;
  for (const auto& [offset, size] : chunks) {
    buffer.resize(size);  // within the file: scan_xdf checked it
    bytes.read(offset, buffer.data(), size, bytes.path());
    out.write(buffer.data(), static_cast<std::streamsize>(size));
  }
  const uint8_t end[2] = {1, 0};
  out.write(reinterpret_cast<const char*>(end), 2);
  out.close();
  if (!out) throw Error(out_path, "cannot write the copy libxdf reads");
}

//---- Choosing streams ------------------------------------------------------------------------

bool xdf_matches(const XdfStreamInfo& stream, const std::string& choice) {
  if (choice.rfind("type:", 0) == 0) return stream.type == choice.substr(5);
  return stream.name == choice;
}

const XdfStreamInfo* xdf_choose(const std::vector<XdfStreamInfo>& streams, bool markers,
                                const std::string& choice, const std::string& path) {
  const char* option = markers ? "--markers" : "--stream";
  std::vector<XdfStreamInfo> candidates;
  for (const XdfStreamInfo& stream : streams) {
    if ((stream.format == "string") != markers) continue;
    if (choice.empty() ? (markers || stream.rate_hz > 0.0) : xdf_matches(stream, choice))
      candidates.push_back(stream);
  }
  if (candidates.size() == 1) {
    for (const XdfStreamInfo& stream : streams)
      if (stream.id == candidates.front().id) return &stream;
  }
  if (candidates.empty() && markers && choice.empty()) return nullptr;
  const char* kind =
      markers ? "markers streams (channel format string)"
              : (choice.empty() ? "numeric streams with a nominal rate" : "numeric streams");
  if (candidates.empty())
    throw Error(option, path + " has no " + (choice.empty() ? "" : "'" + choice + "' among its ") +
                            kind + "; its streams:\n" + xdf_stream_list(streams));
  throw Error(option, path + " has " + std::to_string(candidates.size()) + " " + kind +
                          (choice.empty() ? "" : " matching '" + choice + "'") +
                          ": name one (NAME or type:TYPE):\n" + xdf_stream_list(candidates));
}

}  // namespace

//---- Public ----------------------------------------------------------------------------------

std::vector<XdfStreamInfo> scan_xdf(const std::string& path) {
  XdfBytes bytes(path);
  char magic[4] = {};
  if (bytes.size() < 4)
    throw Error(path, "not an XDF file (" + std::to_string(bytes.size()) + " bytes)");
  bytes.read(0, magic, 4, path);
  if (std::memcmp(magic, "XDF:", 4) != 0)
    throw Error(path, "not an XDF file (no \"XDF:\" at byte 0)");
  std::vector<XdfStreamInfo> streams;
  std::map<uint32_t, size_t> index_of;
  uint64_t offset = 4;
  for (int64_t chunk = 0; offset < bytes.size(); ++chunk) {
    const std::string where =
        path + " chunk " + std::to_string(chunk) + " at byte " + std::to_string(offset);
    uint8_t width = 0;
    bytes.read(offset, &width, 1, where);
    if (width != 1 && width != 4 && width != 8)
      throw Error(where, "length width " + std::to_string(width) + " (XDF allows 1, 4 or 8)");
    uint64_t length = 0;  // little-endian, as wide as it says
    bytes.read(offset + 1, &length, width, where);
    const uint64_t start = offset + 1 + width;
    if (length < 2 || length > bytes.size() - start)
      throw Error(where, "declares " + std::to_string(length) + " bytes, " +
                             std::to_string(bytes.size() - start) + " are left in the file");
    uint16_t tag = 0;
    bytes.read(start, &tag, 2, where);
    const uint64_t content_size = length - 2;
    const uint64_t next = start + length;
    const bool has_stream_id = tag == 2 || tag == 3 || tag == 4 || tag == 6;
    if (tag == 1 || tag == 2) {
      if (content_size > kMaxXdfXmlBytes)
        throw Error(where, "an XML chunk of " + std::to_string(content_size) + " bytes (at most " +
                               std::to_string(kMaxXdfXmlBytes) + ")");
    }
    if (has_stream_id && content_size < 4) throw Error(where, "too short for its stream id");
    if (tag == 1) {
      std::string xml(content_size, '\0');
      bytes.read(start + 2, xml.data(), content_size, where);
      tinyxml2::XMLDocument document;
      if (document.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS)
        throw Error(where, std::string("file header is not XML: ") + document.ErrorStr());
    } else if (tag == 2) {
      XdfStreamInfo stream;
      bytes.read(start + 2, &stream.id, 4, where);
      const std::string place = where + " (stream " + std::to_string(stream.id) + ")";
      if (index_of.count(stream.id)) throw Error(place, "a second header for the stream");
      std::string xml(content_size - 4, '\0');
      bytes.read(start + 6, xml.data(), xml.size(), place);
      xdf_read_header(xml, stream, place);
      index_of[stream.id] = streams.size();
      streams.push_back(std::move(stream));
    } else if (tag == 3 || tag == 4) {
      uint32_t id = 0;
      bytes.read(start + 2, &id, 4, where);
      const std::string place = where + " (stream " + std::to_string(id) + ")";
      const auto found = index_of.find(id);
      if (found == index_of.end())
        throw Error(place, "samples or clock offsets before the stream's header");
      XdfStreamInfo& stream = streams[found->second];
      std::vector<uint8_t> content(content_size - 4);  // within the file, checked above
      bytes.read(start + 6, content.data(), content.size(), place);
      XdfCursor cursor{content};
      if (tag == 3) {
        stream.samples += static_cast<int64_t>(xdf_check_samples(cursor, stream, place));
        stream.sample_chunks.emplace_back(offset, next - offset);
      } else {
        if (content.size() != 16)
          throw Error(place, "a clock offset of " + std::to_string(content.size()) +
                                 " bytes (16: two doubles)");
        const auto time = xdf_take<double>(cursor, place, "the collection time");
        const auto value = xdf_take<double>(cursor, place, "the offset");
        if (!std::isfinite(time) || !std::isfinite(value))
          throw Error(place, "clock offset is not a finite number");
        stream.clock_offsets.emplace_back(time, value);
      }
    }
    // Tags 5 (boundary) and 6 (footer) and tags XDF may add later are skipped: libxdf never
    // sees them.
    offset = next;
  }
  // Offsets stay in the file's order: sorting them by collection time would mix the
  // measurements from before a clock reset with those after it (clock_corrected_stamps).
  return streams;
}

std::string xdf_stream_list(const std::vector<XdfStreamInfo>& streams) {
  std::string list;
  for (const XdfStreamInfo& stream : streams) {
    if (!list.empty()) list += "\n";
    list +=
        "  " + in_quotes(printable_text(stream.name)) + " (type " +
        in_quotes(printable_text(stream.type)) + ", " + std::to_string(stream.channels) + " " +
        stream.format + (stream.channels == 1 ? " channel, " : " channels, ") +
        (stream.rate_hz > 0.0 ? shortest_text(stream.rate_hz) + " Hz" : std::string("irregular")) +
        ", " + std::to_string(stream.samples) + " samples)";
  }
  return list;
}

ImportedRecording import_xdf(const std::string& path, const SkinLayout& layout,
                             const XdfImportOptions& options) {
  const std::vector<XdfStreamInfo> streams = scan_xdf(path);
  const XdfStreamInfo* data = xdf_choose(streams, false, options.stream, path);
  const XdfStreamInfo* markers = xdf_choose(streams, true, options.markers, path);
  const std::string data_where = path + " stream " + in_quotes(printable_text(data->name));
  if (!(data->rate_hz > 0.0))
    throw Error(data_where, "has no nominal rate (irregular): it cannot be resampled onto one");
  const auto channels = static_cast<int64_t>(layout.channels.size());
  if (data->channels != channels)
    throw Error(data_where, "has " + std::to_string(data->channels) + " channels, layout " +
                                layout.id + " has " + std::to_string(channels));
  if (data->samples < 1) throw Error(data_where, "has no samples");

  // libxdf reads the canonical copy (see xdf_write_copy): only what was checked above.
  std::vector<const XdfStreamInfo*> chosen{data};
  if (markers) chosen.push_back(markers);
  XdfTemporaryFile copy;
  {
    XdfBytes bytes(path);
    xdf_write_copy(bytes, chosen, copy.path);
  }
  Xdf xdf;
  int status = 0;
  {
    XdfMuteScope mute;
    status = xdf.load_xdf(copy.path);
  }
  // The copy holds the data stream's header first, so libxdf's stream 0 is it, 1 the markers.
  if (status != 0 || xdf.streams.empty() ||
      static_cast<int64_t>(xdf.streams.front().time_stamps.size()) != data->samples ||
      static_cast<int64_t>(xdf.streams.front().time_series.size()) != channels)
    throw Error(path, "libxdf could not read the checked copy of stream " +
                          in_quotes(printable_text(data->name)));
  const Xdf::Stream& loaded = xdf.streams.front();
  const std::vector<double> stamps =
      clock_corrected_stamps(loaded.time_stamps, data->clock_offsets);
  for (size_t k = 0; k < stamps.size(); ++k) {
    if (!std::isfinite(stamps[k]))
      throw Error(data_where + " sample " + std::to_string(k),
                  "time stamp " + shortest_text(loaded.time_stamps[k]) +
                      " with its clock offset is no finite time");
  }
  SampleMatrix samples(data->samples, channels);
  for (int64_t column = 0; column < channels; ++column) {
    const std::vector<float>& values = loaded.time_series[static_cast<size_t>(column)];
    if (static_cast<int64_t>(values.size()) != data->samples)
      throw Error(path, "libxdf could not read the checked copy of stream " +
                            in_quotes(printable_text(data->name)));
    for (int64_t row = 0; row < data->samples; ++row) {
      const float value = values[static_cast<size_t>(row)];
      if (std::isinf(value))
        throw Error(
            data_where + " sample " + std::to_string(row) + " channel " + std::to_string(column),
            "an infinite value");
      samples(row, column) = value;  // NaN stays: a gap
    }
  }

  ImportedRecording imported;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = data->rate_hz;
  for (const Channel& channel : layout.channels) {
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
  }
  stream.samples = resample_to_rate(stamps, samples, data->rate_hz, data_where);
  const double first = stamps.front();
  const double end_time = static_cast<double>(stream.samples.rows()) / data->rate_hz;
  imported.recording.id = std::filesystem::path(path).stem().string();
  imported.recording.layout_id = layout.id;
  imported.recording.metadata["imported_from"] = std::filesystem::path(path).filename().string();
  imported.recording.metadata["xdf_stream"] = data->name;
  imported.recording.metadata["xdf_first_timestamp"] = shortest_text(first);
  imported.recording.streams.push_back(std::move(stream));
  if (markers) {
    imported.recording.metadata["xdf_markers"] = markers->name;
    // libxdf keeps each stream's events in the file's order, the order clock resets are
    // told in (clock_corrected_stamps).
    std::vector<std::string> texts;
    std::vector<double> raw_stamps;
    for (const auto& [event, stream_index] : xdf.eventMap) {
      if (stream_index != 1) continue;
      texts.push_back(event.first);
      raw_stamps.push_back(event.second);
    }
    const std::vector<double> times = clock_corrected_stamps(raw_stamps, markers->clock_offsets);
    const std::string markers_where = path + " stream " + in_quotes(printable_text(markers->name));
    std::vector<XdfMarker> events;
    for (size_t k = 0; k < texts.size(); ++k) {
      // A markers stream with a rate sends a sample every tick, an empty one when nothing
      // happened: those are no markers (on an irregular stream an empty marker ends a label).
      if (markers->rate_hz > 0.0 && texts[k].empty()) continue;
      const double time = times[k] - first;
      if (!std::isfinite(time))
        throw Error(markers_where, "marker " + in_quotes(printable_text(texts[k])) +
                                       " is at no finite time on the data stream's clock");
      events.push_back({time, texts[k]});
    }
    std::stable_sort(events.begin(), events.end(),
                     [](const XdfMarker& a, const XdfMarker& b) { return a.time < b.time; });
    XdfMarkerLabels paired =
        labels_from_markers(events, end_time, 1.0 / data->rate_hz, markers_where);
    imported.labels = std::move(paired.labels);
    if (!paired.dropped.empty())
      imported.recording.metadata["dropped_labels"] = joined(paired.dropped, "; ");
  }
  return imported;
}

}  // namespace tactile
