#pragma once
// A small XDF writer for tests (XDF 1.0, github.com/sccn/xdf/wiki/Specifications): the magic
// "XDF:", then chunks of [NumLengthBytes 1|4|8][Length][Tag uint16][content], little-endian.
// Tags: FileHeader 1, StreamHeader 2, Samples 3, ClockOffset 4, Boundary 5, StreamFooter 6.
// Lengths are written in the narrowest width that holds them, as LabRecorder does.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace tactile::testing {

class XdfWriter {
 public:
  // `nul_after_xml`: each XML chunk ends in a NUL byte, which libxdf needs to read a file
  // itself without reading past its buffers (the importer gives it such a copy); files
  // from LabRecorder have none.
  explicit XdfWriter(bool nul_after_xml = false) : nul_after_xml_(nul_after_xml) {
    bytes_ = "XDF:";
    chunk(1, xml("<?xml version=\"1.0\"?><info><version>1.0</version></info>"));
  }

  void stream_header(uint32_t id, const std::string& name, const std::string& type, int channels,
                     double rate_hz, const std::string& format) {
    char rate[64];
    std::snprintf(rate, sizeof rate, "%.17g", rate_hz);
    chunk(2, id_bytes(id) +
                 xml("<?xml version=\"1.0\"?>\n<info><name>" + name + "</name><type>" + type +
                     "</type><channel_count>" + std::to_string(channels) +
                     "</channel_count><nominal_srate>" + rate + "</nominal_srate><channel_format>" +
                     format + "</channel_format><source_id>test</source_id><desc/></info>"));
  }

  // float32 samples; a NaN stamp is written as "no stamp" (deduced by the reader).
  void float_samples(uint32_t id, const std::vector<double>& stamps,
                     const std::vector<std::vector<float>>& values) {
    std::string content = id_bytes(id) + length_bytes(stamps.size());
    for (size_t k = 0; k < stamps.size(); ++k) {
      content += stamp_bytes(stamps[k]);
      for (float value : values[k]) content += raw(&value, 4);
    }
    chunk(3, content);
  }

  void string_samples(uint32_t id, const std::vector<double>& stamps,
                      const std::vector<std::string>& texts) {
    std::string content = id_bytes(id) + length_bytes(stamps.size());
    for (size_t k = 0; k < stamps.size(); ++k)
      content += stamp_bytes(stamps[k]) + length_bytes(texts[k].size()) + texts[k];
    chunk(3, content);
  }

  void clock_offset(uint32_t id, double collection_time, double offset) {
    chunk(4, id_bytes(id) + raw(&collection_time, 8) + raw(&offset, 8));
  }

  void boundary() { chunk(5, std::string(16, '\x42')); }

  void footer(uint32_t id, int64_t samples) {
    chunk(6, id_bytes(id) + xml("<?xml version=\"1.0\"?><info><sample_count>" +
                                std::to_string(samples) + "</sample_count></info>"));
  }

  // Any chunk, for files that break the rules.
  void chunk(uint16_t tag, const std::string& content) {
    bytes_ += length_bytes(content.size() + 2) + raw(&tag, 2) + content;
  }
  void append(const std::string& bytes) { bytes_ += bytes; }

  const std::string& bytes() const { return bytes_; }
  void save(const std::string& path) const {
    std::ofstream out(path, std::ios::binary);
    out << bytes_;
  }

  static std::string raw(const void* data, size_t size) {
    return std::string(static_cast<const char*>(data), size);
  }
  static std::string id_bytes(uint32_t id) { return raw(&id, 4); }
  static std::string length_bytes(uint64_t length) {
    if (length <= 0xff) return std::string(1, '\x01') + static_cast<char>(length);
    if (length <= 0xffffffffu) {
      const auto narrow = static_cast<uint32_t>(length);
      return std::string(1, '\x04') + raw(&narrow, 4);
    }
    return std::string(1, '\x08') + raw(&length, 8);
  }
  static std::string stamp_bytes(double stamp) {
    if (std::isnan(stamp)) return std::string(1, '\0');
    return std::string(1, '\x08') + raw(&stamp, 8);
  }

 private:
  std::string xml(const std::string& text) const { return nul_after_xml_ ? text + '\0' : text; }

  bool nul_after_xml_ = false;
  std::string bytes_;
};

}  // namespace tactile::testing

namespace tactile::testing {

// The session of tests/data/interop/glove_session.xdf: a glove of 8 float32 channels at
// 100 Hz ("TactileGlove", type Tactile, stream 1) whose stamps jitter by up to 2 ms, with a
// dropout (samples 31-35 never sent) and three samples sent without a stamp (10-12: the
// reader deduces them from the one before); a markers stream ("Touches", type Markers,
// stream 2); clock offsets of +0.25 s (glove) and +0.3 s (markers); a boundary chunk and
// both footers.
struct XdfGloveSample {
  int index = 0;        // 0..59
  double stamp = 0.0;   // as the reader sees it, before clock correction
  bool stamped = true;  // written with its stamp
  float value(int channel) const { return static_cast<float>(100 * channel + index) + 0.25f; }
};

inline std::vector<XdfGloveSample> xdf_glove_samples() {
  std::vector<XdfGloveSample> samples;
  double last = 0.0;
  for (int k = 0; k < 60; ++k) {
    if (k >= 31 && k <= 35) continue;  // the dropout
    XdfGloveSample sample;
    sample.index = k;
    sample.stamped = k < 10 || k > 12;
    sample.stamp = sample.stamped ? 1000.0 + 0.01 * k + 0.001 * ((k * 7) % 5 - 2) : last + 0.01;
    last = sample.stamp;
    samples.push_back(sample);
  }
  return samples;
}

struct XdfGloveMarker {
  double stamp;
  std::string text;
};

inline std::vector<XdfGloveMarker> xdf_glove_markers() {
  return {{1000.10, "stroke"}, {1000.20, "none"}, {1000.25, "pat start"}, {1000.40, "pat end"},
          {1000.45, "poke"},   {1000.50, ""},     {1000.52, "Tap BEGIN"}, {1000.56, "Tap End"}};
}

inline XdfWriter xdf_glove_session(bool nul_after_xml = false) {
  XdfWriter writer(nul_after_xml);
  writer.stream_header(1, "TactileGlove", "Tactile", 8, 100.0, "float32");
  writer.stream_header(2, "Touches", "Markers", 1, 0.0, "string");
  writer.clock_offset(1, 999.0, 0.25);
  writer.clock_offset(2, 999.0, 0.3);
  const std::vector<XdfGloveSample> samples = xdf_glove_samples();
  const std::vector<XdfGloveMarker> markers = xdf_glove_markers();
  auto glove_chunk = [&](int from, int to) {
    std::vector<double> stamps;
    std::vector<std::vector<float>> values;
    for (const XdfGloveSample& sample : samples) {
      if (sample.index < from || sample.index >= to) continue;
      stamps.push_back(sample.stamped ? sample.stamp : std::nan(""));
      std::vector<float> row;
      for (int channel = 0; channel < 8; ++channel) row.push_back(sample.value(channel));
      values.push_back(std::move(row));
    }
    writer.float_samples(1, stamps, values);
  };
  auto marker_chunk = [&](size_t from, size_t to) {
    std::vector<double> stamps;
    std::vector<std::string> texts;
    for (size_t k = from; k < to; ++k) {
      stamps.push_back(markers[k].stamp);
      texts.push_back(markers[k].text);
    }
    writer.string_samples(2, stamps, texts);
  };
  glove_chunk(0, 20);
  marker_chunk(0, 3);
  glove_chunk(20, 40);
  writer.boundary();
  marker_chunk(3, 6);
  glove_chunk(40, 60);
  marker_chunk(6, 8);
  writer.clock_offset(1, 1001.0, 0.25);
  writer.clock_offset(2, 1001.0, 0.3);
  writer.footer(1, 55);
  writer.footer(2, 8);
  return writer;
}

}  // namespace tactile::testing
