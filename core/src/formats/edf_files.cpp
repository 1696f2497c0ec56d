#include "tactile/formats/edf_files.h"

#include <edflib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>

#include "tactile/error.h"
#include "tactile/formats/array_files.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// The main header's fields (EDF specification): byte offset and width.
constexpr size_t kEdfMainHeaderBytes = 256;
constexpr size_t kEdfReservedOffset = 192, kEdfRecordsOffset = 236, kEdfSignalCountOffset = 252;
// Per signal: label 16, transducer 80, dimension 8, physical min/max 8 + 8, digital min/max
// 8 + 8, prefilter 80, samples per record 8, reserved 32.
constexpr size_t kEdfSignalHeaderBytes = 256;
constexpr size_t kEdfSamplesPerRecordOffset = 16 + 80 + 8 + 8 + 8 + 8 + 8 + 80;
// EDFlib's own limits: at most 640 signals; a data record of at most 10 MB (EDF) or 15 MB (BDF).
constexpr long long kEdfMaxSignals = EDFLIB_MAXSIGNALS;

std::string edf_trimmed(std::string text) {
  const auto is_space = [](unsigned char c) { return std::isspace(c) != 0; };
  while (!text.empty() && is_space(static_cast<unsigned char>(text.back()))) text.pop_back();
  size_t first = 0;
  while (first < text.size() && is_space(static_cast<unsigned char>(text[first]))) ++first;
  return text.substr(first);
}

std::string edf_field(const std::vector<unsigned char>& header, size_t offset, size_t width) {
  return edf_trimmed(std::string(reinterpret_cast<const char*>(header.data()) + offset, width));
}

// A field as a refusal quotes it: a damaged header holds any bytes, a NUL among them.
std::string edf_quoted_field(const std::vector<unsigned char>& header, size_t offset,
                             size_t width) {
  return in_quotes(printable_text(edf_field(header, offset, width)));
}

// An integer field (ASCII, space padded); nullopt when it is not one.
std::optional<long long> edf_integer(const std::vector<unsigned char>& header, size_t offset,
                                     size_t width) {
  const std::string text = edf_field(header, offset, width);
  long long value = 0;
  const char* begin = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
  const auto [end, error] = std::from_chars(begin, text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::string edf_byte_place(const std::string& where, size_t offset) {
  return where + " byte " + std::to_string(offset);
}

// EDFlib's error codes, as a reader would say them.
std::string edf_open_error(int code) {
  switch (code) {
    case EDFLIB_MALLOC_ERROR:
      return "EDFlib could not allocate memory";
    case EDFLIB_NO_SUCH_FILE_OR_DIRECTORY:
      return "cannot open the file";
    case EDFLIB_FILE_CONTAINS_FORMAT_ERRORS:
      return "not a valid EDF(+) or BDF(+) file (EDFlib found format errors in its header or "
             "annotations)";
    case EDFLIB_MAXFILES_REACHED:
      return "too many EDF files open at once";
    case EDFLIB_FILE_READ_ERROR:
      return "a read error";
    case EDFLIB_FILE_ALREADY_OPENED:
      return "the file is open already";
    case EDFLIB_FILETYPE_ERROR:
      return "not an EDF or BDF file";
    case EDFLIB_FILE_IS_DISCONTINUOUS:
      return "EDF+D (discontinuous) is not read";
    case EDFLIB_INVALID_READ_ANNOTS_VALUE:
      return "EDFlib refused the annotation mode";
    default:
      return "EDFlib error " + std::to_string(code);
  }
}

// EDFlib keeps its open files in a global table (edfopen_file_readonly and edfclose_file are not
// thread-safe): one file at a time, whichever thread imports.
std::mutex& edf_library_mutex() {
  static std::mutex mutex;
  return mutex;
}

struct EdfHandle {
  int handle = -1;
  ~EdfHandle() {
    if (handle >= 0) edfclose_file(handle);
  }
};

std::string edf_two_digits(int value) {
  char text[8];
  std::snprintf(text, sizeof text, "%02d", value);
  return text;
}

void edf_metadata(const edf_hdr_struct& header, Metadata& metadata) {
  const bool plus =
      header.filetype == EDFLIB_FILETYPE_EDFPLUS || header.filetype == EDFLIB_FILETYPE_BDFPLUS;
  const char* formats[] = {"EDF", "EDF+", "BDF", "BDF+"};
  metadata["edf_format"] = formats[std::clamp(header.filetype, 0, 3)];
  std::string start =
      std::to_string(header.startdate_year) + "-" + edf_two_digits(header.startdate_month) + "-" +
      edf_two_digits(header.startdate_day) + "T" + edf_two_digits(header.starttime_hour) + ":" +
      edf_two_digits(header.starttime_minute) + ":" + edf_two_digits(header.starttime_second);
  if (header.starttime_subsecond > 0) {
    char fraction[32];
    std::snprintf(fraction, sizeof fraction, ".%07lld", header.starttime_subsecond);
    std::string digits = fraction;
    while (digits.back() == '0') digits.pop_back();
    start += digits;
  }
  metadata["start_time"] = start;
  // EDF+ writes "X" for a subfield nobody knows: left out like an empty one.
  const auto put = [&](const char* key, const char* value) {
    const std::string text = edf_trimmed(value);
    if (!text.empty() && !(plus && text == "X")) metadata[key] = text;
  };
  if (!plus) {
    put("patient", header.patient);
    put("recording", header.recording);
    return;
  }
  put("patient_code", header.patientcode);
  put("patient_name", header.patient_name);
  put("patient_sex", header.gender);
  put("patient_birthdate", header.birthdate);
  put("patient_additional", header.patient_additional);
  put("admin_code", header.admincode);
  put("technician", header.technician);
  put("equipment", header.equipment);
  put("recording_additional", header.recording_additional);
}

// The file's signals named by `wanted` (or every one), in that order; the index EDFlib gives each.
std::vector<int> edf_chosen_signals(const edf_hdr_struct& header,
                                    const std::vector<std::string>& wanted,
                                    const std::string& where) {
  std::vector<std::string> labels;
  for (int signal = 0; signal < header.edfsignals; ++signal)
    labels.push_back(edf_trimmed(header.signalparam[signal].label));
  std::vector<int> chosen;
  if (wanted.empty()) {
    for (int signal = 0; signal < header.edfsignals; ++signal) chosen.push_back(signal);
    return chosen;
  }
  for (const std::string& name : wanted) {
    const std::string label = edf_trimmed(name);
    if (label == "EDF Annotations" || label == "BDF Annotations")
      throw Error("--signals", label + " is the annotation signal of " + where +
                                   ": its annotations become labels, not samples");
    const auto count = std::count(labels.begin(), labels.end(), label);
    if (count == 0)
      throw Error("--signals", "no signal " + in_quotes(label) + " in " + where +
                                   "; its signals: " + tactile::joined(labels));
    if (count > 1)
      throw Error("--signals", std::to_string(count) + " signals of " + where + " are labelled " +
                                   in_quotes(label) + "; one label must name one signal");
    const int signal =
        static_cast<int>(std::find(labels.begin(), labels.end(), label) - labels.begin());
    if (std::find(chosen.begin(), chosen.end(), signal) != chosen.end())
      throw Error("--signals", in_quotes(label) + " is named twice");
    chosen.push_back(signal);
  }
  return chosen;
}

// The annotations as labels on the data [0, end): EDF+ puts no bound on an onset, and
// EDFbrowser and clinical recorders write "Recording ends" (or the like) at the last instant,
// the data's end. A label is a stretch of the data, so an annotation that starts at or after
// the end is no label: it is dropped and named in `dropped`. One that starts inside and runs
// past the end is clipped to it; what is left shorter than one sample (`sample_seconds`) is
// dropped the same way (no sample to label, and ELAN cannot hold under a millisecond).
std::vector<Label> edf_labels(int handle, const edf_hdr_struct& header,
                              const EdfImportOptions& options, double sample_seconds,
                              const std::string& where, std::vector<std::string>& dropped) {
  // The end in EDFlib's units (100 ns), as onsets are: "at or after" compares exactly.
  const long long end_units = header.datarecords_in_file * header.datarecord_duration;
  const double end = static_cast<double>(end_units) / EDFLIB_TIME_DIMENSION;
  std::vector<Label> labels;
  for (long long index = 0; index < header.annotations_in_file; ++index) {
    edf_annotation_struct annotation{};
    if (edf_get_annotation(handle, static_cast<int>(index), &annotation) != 0)
      throw Error(where + " annotation " + std::to_string(index + 1), "EDFlib could not read it");
    annotation.annotation[EDFLIB_MAX_ANNOTATION_LEN] = '\0';
    const std::string text = edf_trimmed(annotation.annotation);
    const double onset = static_cast<double>(annotation.onset) / EDFLIB_TIME_DIMENSION;
    const std::string named = "annotation " + std::to_string(index + 1) + " at " +
                              shortest_text(onset) + " s " + in_quotes(printable_text(text));
    const std::string place = where + " " + named;
    if (text.empty()) throw Error(place, "has no text (a label needs a class)");
    if (onset < 0.0) throw Error(place, "starts before the recording");
    if (annotation.onset >= end_units) {
      dropped.push_back(named + ": at or after the data's end (" + shortest_text(end) + " s)");
      continue;
    }
    double duration = annotation.duration_l > 0
                          ? static_cast<double>(annotation.duration_l) / EDFLIB_TIME_DIMENSION
                          : 0.0;
    if (!(duration > 0.0)) {
      if (!options.annotation_seconds)
        throw Error(place, std::string("has ") + (annotation.duration_l == 0 ? "zero" : "no") +
                               " duration: give such annotations a length with "
                               "--annotation-seconds S");
      duration = *options.annotation_seconds;
    }
    // Clipped to the data; a millionth of a sample absorbs the rounding of the times.
    if (onset + duration > end && end - onset < sample_seconds * (1.0 - 1e-6)) {
      dropped.push_back(named + ": starts " + shortest_text(end - onset) +
                        " s before the data's end (" + shortest_text(end) +
                        " s), less than one sample (" + shortest_text(sample_seconds) + " s)");
      continue;
    }
    Label label;
    label.t0 = onset;
    label.t1 = std::min(onset + duration, end);
    label.region = "all";
    label.class_name = text;
    label.annotator = "import";
    label.source = LabelSource::kGroundTruth;
    labels.push_back(std::move(label));
  }
  return labels;
}

}  // namespace

void check_edf_header(const std::vector<unsigned char>& header, long long file_size,
                      const std::string& where) {
  if (header.size() < kEdfMainHeaderBytes ||
      file_size < static_cast<long long>(kEdfMainHeaderBytes))
    throw Error(where, "holds " + std::to_string(file_size) +
                           " bytes, less than the 256-byte header of an EDF or BDF file");
  const bool bdf =
      header[0] == 0xff && std::equal(header.begin() + 1, header.begin() + 8,
                                      reinterpret_cast<const unsigned char*>("BIOSEMI"));
  if (!bdf && edf_field(header, 0, 8) != "0")
    throw Error(edf_byte_place(where, 0),
                "not an EDF or BDF file (the version field is neither \"0\" nor \\xffBIOSEMI)");
  const std::string reserved = edf_field(header, kEdfReservedOffset, 44);
  if (reserved.rfind("EDF+D", 0) == 0 || reserved.rfind("BDF+D", 0) == 0)
    throw Error(edf_byte_place(where, kEdfReservedOffset),
                reserved.substr(0, 5) +
                    " (discontinuous) is not read: EDFlib does not give the onsets of its data "
                    "records, so its gaps cannot be placed; convert it to " +
                    reserved.substr(0, 3) + "+C first");
  const std::optional<long long> signals = edf_integer(header, kEdfSignalCountOffset, 4);
  if (!signals || *signals < 1 || *signals > kEdfMaxSignals)
    throw Error(edf_byte_place(where, kEdfSignalCountOffset),
                "number of signals " + edf_quoted_field(header, kEdfSignalCountOffset, 4) +
                    ", expected 1 to " + std::to_string(kEdfMaxSignals));
  const long long header_bytes = static_cast<long long>(kEdfMainHeaderBytes) +
                                 *signals * static_cast<long long>(kEdfSignalHeaderBytes);
  if (file_size < header_bytes || static_cast<long long>(header.size()) < header_bytes)
    throw Error(where, "holds " + std::to_string(file_size) + " bytes, less than the " +
                           std::to_string(header_bytes) + "-byte header its " +
                           std::to_string(*signals) + " signals need");
  const std::optional<long long> records = edf_integer(header, kEdfRecordsOffset, 8);
  if (!records || *records < 1)
    throw Error(edf_byte_place(where, kEdfRecordsOffset),
                "number of data records " + edf_quoted_field(header, kEdfRecordsOffset, 8) +
                    (records && *records == -1 ? ": unknown (the recording was never closed)"
                                               : ", expected a count of at least 1"));
  const long long sample_bytes = bdf ? 3 : 2;
  const long long max_record_bytes = (bdf ? 15 : 10) * 1024LL * 1024LL;
  long long record_bytes = 0;
  for (long long signal = 0; signal < *signals; ++signal) {
    const size_t offset = kEdfMainHeaderBytes +
                          static_cast<size_t>(*signals) * kEdfSamplesPerRecordOffset +
                          static_cast<size_t>(signal) * 8;
    const std::optional<long long> samples = edf_integer(header, offset, 8);
    if (!samples || *samples < 1 || *samples > max_record_bytes)
      throw Error(edf_byte_place(where, offset),
                  "signal " + std::to_string(signal + 1) + "'s samples per data record " +
                      edf_quoted_field(header, offset, 8) + ", expected a count of at least 1");
    record_bytes += *samples * sample_bytes;
  }
  if (record_bytes > max_record_bytes)
    throw Error(edf_byte_place(where, kEdfMainHeaderBytes + static_cast<size_t>(*signals) *
                                                                kEdfSamplesPerRecordOffset),
                "a data record of " + std::to_string(record_bytes) + " bytes, more than the " +
                    std::to_string(max_record_bytes) + " EDFlib reads");
  // records * record_bytes without overflow: both are checked against what the file holds.
  if (*records > (file_size - header_bytes) / record_bytes)
    throw Error(edf_byte_place(where, kEdfRecordsOffset),
                std::to_string(*records) + " data records of " + std::to_string(record_bytes) +
                    " bytes after the " + std::to_string(header_bytes) +
                    "-byte header, but the file holds " + std::to_string(file_size) + " bytes");
}

ImportedRecording import_edf(const std::string& path, const SkinLayout& layout,
                             const EdfImportOptions& options) {
  namespace fs = std::filesystem;
  if (options.annotation_seconds &&
      (!(*options.annotation_seconds > 0.0) || !std::isfinite(*options.annotation_seconds)))
    throw Error("--annotation-seconds", "a length above 0 seconds is needed");
  // The header, read here and checked before EDFlib sees the file (edf_files.h says why).
  std::error_code size_error;
  const auto file_size = static_cast<long long>(fs::file_size(path, size_error));
  if (size_error) throw Error(path, "cannot read: " + size_error.message());
  std::vector<unsigned char> header(static_cast<size_t>(std::min<long long>(
      file_size, kEdfMainHeaderBytes + kEdfMaxSignals * kEdfSignalHeaderBytes)));
  {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                         std::fclose);
    if (!file) throw Error(path, system_error("cannot open"));
    if (std::fread(header.data(), 1, header.size(), file.get()) != header.size())
      throw Error(path, "cannot read its header");
  }
  check_edf_header(header, file_size, path);

  std::lock_guard<std::mutex> lock(edf_library_mutex());
  // The header struct holds 640 signals' parameters (some 200 kB): not on the stack.
  auto edf = std::make_unique<edf_hdr_struct>();
  EdfHandle handle;
  if (edfopen_file_readonly(path.c_str(), edf.get(), EDFLIB_READ_ALL_ANNOTATIONS) != 0)
    throw Error(path, edf_open_error(edf->filetype));
  handle.handle = edf->handle;
  if (edf->edfsignals < 1) throw Error(path, "has no signals, only annotations");
  if (!(edf->datarecord_duration > 0))
    throw Error(edf_byte_place(path, 244), "data records of no duration hold no samples at a rate");

  const std::vector<int> chosen = edf_chosen_signals(*edf, options.signals, path);
  std::vector<std::string> names;
  for (int signal : chosen) names.push_back(edf_trimmed(edf->signalparam[signal].label));
  const auto rate_of = [&](int signal) {
    return static_cast<double>(edf->signalparam[signal].smp_in_datarecord) *
           static_cast<double>(EDFLIB_TIME_DIMENSION) /
           static_cast<double>(edf->datarecord_duration);
  };
  for (int signal : chosen) {
    if (edf->signalparam[signal].smp_in_datarecord ==
        edf->signalparam[chosen.front()].smp_in_datarecord)
      continue;
    std::vector<std::string> rates;
    for (int each : chosen)
      rates.push_back(in_quotes(edf_trimmed(edf->signalparam[each].label)) + " " +
                      shortest_text(rate_of(each)) + " Hz");
    throw Error(options.signals.empty() ? path : "--signals",
                "the signals of one stream share one rate; " + path + "'s differ: " +
                    tactile::joined(rates) + " (choose signals of one rate with --signals)");
  }
  const int64_t channels = static_cast<int64_t>(layout.channels.size());
  if (static_cast<int64_t>(chosen.size()) != channels)
    throw Error(options.signals.empty() ? path : "--signals",
                std::to_string(chosen.size()) + " signals (" + tactile::joined(names) +
                    ") do not fit " + layout.id + "'s " + std::to_string(channels) +
                    " channels: choose " + std::to_string(channels) + " with --signals");
  const long long samples = edf->signalparam[chosen.front()].smp_in_file;
  // Within what check_edf_header allowed (the file's bytes), but an import has its own bound.
  if (samples < 0 || samples * channels > kMaxImportedElements)
    throw Error(path, std::to_string(samples) + " samples x " + std::to_string(channels) +
                          " signals, more than an import reads");

  ImportedRecording imported;
  Stream stream;
  stream.name = options.stream_name;
  stream.rate_hz = rate_of(chosen.front());
  for (size_t column = 0; column < chosen.size(); ++column) {
    const edf_param_struct& signal = edf->signalparam[chosen[column]];
    stream.channels.push_back(layout.channels[column].name);
    const std::string unit = edf_trimmed(signal.physdimension);
    stream.units.push_back(unit.empty() ? layout.channels[column].unit : unit);
    if (!std::isfinite(signal.phys_min) || !std::isfinite(signal.phys_max))
      throw Error(path + " signal " + in_quotes(names[column]), "its physical range is not finite");
  }
  stream.samples.resize(samples, channels);
  // A block at a time: the doubles EDFlib gives are never held for the whole file.
  constexpr long long kBlock = 1 << 16;
  std::vector<double> block(static_cast<size_t>(std::min(samples, kBlock)));
  for (size_t column = 0; column < chosen.size(); ++column) {
    if (edfseek(handle.handle, chosen[column], 0, EDFSEEK_SET) != 0)
      throw Error(path + " signal " + in_quotes(names[column]),
                  "EDFlib could not seek to its start");
    for (long long first = 0; first < samples; first += kBlock) {
      const int count = static_cast<int>(std::min(kBlock, samples - first));
      if (edfread_physical_samples(handle.handle, chosen[column], count, block.data()) != count)
        throw Error(
            path + " signal " + in_quotes(names[column]) + " sample " + std::to_string(first),
            "EDFlib could not read its samples");
      for (int k = 0; k < count; ++k) {
        if (!std::isfinite(block[static_cast<size_t>(k)]))
          throw Error(
              path + " signal " + in_quotes(names[column]) + " sample " + std::to_string(first + k),
              "not a finite physical value");
        stream.samples(first + k, static_cast<int64_t>(column)) =
            static_cast<float>(block[static_cast<size_t>(k)]);
      }
    }
  }
  std::vector<std::string> dropped;
  imported.labels = edf_labels(handle.handle, *edf, options, 1.0 / stream.rate_hz, path, dropped);
  if (!dropped.empty())
    imported.recording.metadata["dropped_labels"] = tactile::joined(dropped, "; ");
  imported.recording.id = fs::path(path).stem().string();
  imported.recording.layout_id = layout.id;
  imported.recording.metadata["imported_from"] = fs::path(path).filename().string();
  imported.recording.metadata["edf_signals"] = tactile::joined(names, ",");
  edf_metadata(*edf, imported.recording.metadata);
  imported.recording.streams.push_back(std::move(stream));
  return imported;
}

}  // namespace tactile
