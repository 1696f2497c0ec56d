// tactile verify / tactile upgrade: see tactile/verify/verify.h.
#include "tactile/verify/verify.h"

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/hdf5_object.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {

namespace {

using hdf5::Object;

bool has_extension(const std::string& path, std::initializer_list<const char*> extensions) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const char* known) { return extension == known; });
}

//---- Recordings

// Format 2 promises: a checksummed superblock, Fletcher32 on every chunked dataset,
// no variable-length string (the global heap carries no checksum).
struct StructureWalk {
  std::string path;
  std::vector<FileProblem>* problems;
  void add(const std::string& place, const std::string& what) {
    problems->push_back({path, path + ":/" + place + ": " + what});
  }
};

bool is_variable_string(hid_t type) {
  return H5Tget_class(type) == H5T_STRING && H5Tis_variable_str(type) > 0;
}

herr_t check_attribute(hid_t location, const char* name, const H5A_info_t*, void* data) {
  auto& walk = *static_cast<std::pair<StructureWalk*, std::string>*>(data);
  const hid_t attribute = H5Aopen(location, name, H5P_DEFAULT);
  if (attribute < 0) {
    walk.first->add(walk.second, std::string("attribute ") + name + ": cannot open");
    return 0;
  }
  const hid_t type = H5Aget_type(attribute);
  if (type >= 0 && (is_variable_string(type) || H5Tdetect_class(type, H5T_VLEN) > 0))
    walk.first->add(walk.second, std::string("attribute ") + name + " is variable-length");
  if (type >= 0) H5Tclose(type);
  H5Aclose(attribute);
  return 0;
}

herr_t check_object(hid_t root, const char* name, const H5O_info_t* info, void* data) {
  auto& walk = *static_cast<StructureWalk*>(data);
  const std::string place = std::strcmp(name, ".") == 0 ? "" : name;
  const hid_t object = H5Oopen(root, name, H5P_DEFAULT);
  if (object < 0) {
    walk.add(place, "cannot open (" + hdf5::last_error() + ")");
    return 0;
  }
  std::pair<StructureWalk*, std::string> attribute_walk{&walk, place};
  hsize_t index = 0;
  if (H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, &index, check_attribute, &attribute_walk) < 0)
    walk.add(place, "cannot list attributes (" + hdf5::last_error() + ")");
  if (info->type == H5O_TYPE_DATASET) {
    const hid_t type = H5Dget_type(object);
    if (type >= 0 && (is_variable_string(type) || H5Tdetect_class(type, H5T_VLEN) > 0))
      walk.add(place, "variable-length data, outside every checksum");
    if (type >= 0) H5Tclose(type);
    const hid_t properties = H5Dget_create_plist(object);
    if (properties >= 0) {
      const H5D_layout_t layout = H5Pget_layout(properties);
      bool fletcher = false;
      for (int filter = 0; filter < H5Pget_nfilters(properties); ++filter)
        fletcher =
            fletcher || H5Pget_filter2(properties, static_cast<unsigned>(filter), nullptr, nullptr,
                                       nullptr, 0, nullptr, nullptr) == H5Z_FILTER_FLETCHER32;
      if (layout == H5D_CONTIGUOUS)
        walk.add(place, "contiguous data, outside every checksum");
      else if (layout == H5D_CHUNKED && !fletcher)
        walk.add(place, "chunks without the Fletcher32 checksum");
      H5Pclose(properties);
    }
  }
  H5Oclose(object);
  return 0;
}

void check_structure(const std::string& path, std::vector<FileProblem>& problems) {
  hdf5::silence_errors();
  Object file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid() && hdf5::last_error().find("already open for write") != std::string::npos) {
    // A live recording cut off (or still being written): its structure is checked as it is.
    Object access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    H5Pset_metadata_read_attempts(access.id(), 1);
    file = Object(H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, access.id()), H5Fclose);
  }
  if (!file.valid()) return;  // RecordingFile has said why
  H5F_info2_t info{};
  if (H5Fget_info2(file.id(), &info) >= 0 && info.super.version < 2)
    problems.push_back({path, path + ": superblock version " + std::to_string(info.super.version) +
                                  " carries no checksum"});
  StructureWalk walk{path, &problems};
  if (H5Ovisit2(file.id(), H5_INDEX_NAME, H5_ITER_INC, check_object, &walk, H5O_INFO_BASIC) < 0)
    walk.add("", "cannot walk the file (" + hdf5::last_error() + ")");
}

bool same_float(float left, float right) {
  return std::memcmp(&left, &right, sizeof(float)) == 0 || (std::isnan(left) && std::isnan(right));
}

// Reads a stream chunk by chunk (naming the channel of a chunk that fails) and
// compares the stored overview with the samples.
void verify_stream(const RecordingFile& file, const StreamInfo& stream,
                   std::vector<FileProblem>& problems) {
  const std::string& path = file.path();
  const std::string place = path + ":/streams/" + stream.name;
  auto add = [&](const std::string& where, const std::string& what) {
    problems.push_back({path, where + ": " + what});
  };
  std::optional<std::pair<SampleMatrix, SampleMatrix>> overview;
  try {
    overview = file.read_overview(stream.name);
  } catch (const Error& error) {
    problems.push_back({path, error.what()});
  }
  const int64_t block = file.overview_block();
  const int64_t chunk = std::max<int64_t>(file.chunk_samples(stream.name), 8192);
  const int64_t step = (chunk + block - 1) / block * block;
  const int channels = static_cast<int>(stream.channels.size());
  for (int64_t first = 0; first < stream.sample_count; first += step) {
    const int64_t count = std::min(step, stream.sample_count - first);
    SampleMatrix samples;
    try {
      samples = file.read(stream.name, first, count);
    } catch (const Error&) {
      // Name each channel whose chunk fails.
      for (int channel = 0; channel < channels; ++channel) {
        try {
          file.read_channel(stream.name, channel, first, count);
        } catch (const Error& error) {
          add(place + "/samples", "channel " + stream.channels[static_cast<size_t>(channel)] +
                                      ", samples [" + std::to_string(first) + ", " +
                                      std::to_string(first + count) + "): " + error.message());
        }
      }
      continue;
    }
    if (!overview) continue;
    for (int64_t start = 0; start < count; start += block) {
      const int64_t length = std::min(block, count - start);
      const int64_t index = (first + start) / block;
      for (int channel = 0; channel < channels; ++channel) {
        const auto values = samples.col(channel).segment(start, length);
        const float low = values.minCoeff<Eigen::PropagateNumbers>();
        const float high = values.maxCoeff<Eigen::PropagateNumbers>();
        if (!same_float(low, overview->first(index, channel)) ||
            !same_float(high, overview->second(index, channel))) {
          add(place + "/overview_min", "block " + std::to_string(index) + " of channel " +
                                           stream.channels[static_cast<size_t>(channel)] +
                                           " disagrees with the samples it summarises");
          return;  // one line per stream is enough to name it
        }
      }
    }
  }
  if (stream.has_timestamps) {
    try {
      const std::vector<double> times = file.read_timestamps(stream.name);
      for (size_t index = 0; index < times.size(); ++index)
        if (!std::isfinite(times[index]) || (index > 0 && !(times[index] > times[index - 1]))) {
          add(place + "/timestamps",
              "time stamp " + std::to_string(index) + " is not finite or not after the one before");
          break;
        }
    } catch (const Error& error) {
      problems.push_back({path, error.what()});
    }
  }
}

//---- Label stores

// The schema version, read without opening the store for writing.
int64_t store_version(const std::string& path) {
  sqlite3* database = nullptr;
  int64_t version = -1;
  if (sqlite3_open_v2(path.c_str(), &database, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(database, "SELECT MAX(version) FROM store_schema", -1, &statement,
                           nullptr) == SQLITE_OK &&
        sqlite3_step(statement) == SQLITE_ROW)
      version = sqlite3_column_int64(statement, 0);
    sqlite3_finalize(statement);
  }
  sqlite3_close_v2(database);
  return version;
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

}  // namespace

FileKind file_kind(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[16] = {};
  in.read(head, sizeof(head));
  if (in.gcount() >= 8 && std::memcmp(head, "\x89HDF\r\n\x1a\n", 8) == 0)
    return FileKind::kRecording;
  if (in.gcount() == 16 && std::memcmp(head, "SQLite format 3", 16) == 0)
    return FileKind::kLabelStore;
  if (has_extension(path, {".h5", ".hdf5"})) return FileKind::kRecording;
  if (has_extension(path, {".db", ".sqlite", ".sqlite3"})) return FileKind::kLabelStore;
  return FileKind::kUnknown;
}

namespace {

// The span of an open recording, from its streams' headers: from the earliest start to the
// latest end. None for a recording without streams.
void note_recording_span(const RecordingFile& file, RecordingSpans& spans) {
  double begin = 0.0, end = 0.0;
  bool first_stream = true;
  for (const StreamInfo& stream : file.streams()) {
    const double start = stream.has_timestamps ? stream.first_timestamp : stream.start_time;
    begin = first_stream ? start : std::min(begin, start);
    end = first_stream ? start + stream.duration() : std::max(end, start + stream.duration());
    first_stream = false;
  }
  if (!first_stream) spans[file.recording_id()] = {begin, end};
}

// A recording another shard checks: only its span, as verify_recording notes it (none when
// it does not open).
void add_recording_span(const std::string& path, RecordingSpans& spans) {
  try {
    note_recording_span(RecordingFile(path), spans);
  } catch (const Error&) {
  }
}

}  // namespace

std::vector<FileProblem> verify_recording(const std::string& path, RecordingSpans* spans) {
  std::vector<FileProblem> problems;
  std::optional<RecordingFile> file;
  try {
    file.emplace(path);
  } catch (const Error& error) {
    problems.push_back({path, error.what()});
    return problems;
  }
  if (file->format_version() < kRecordingFormatVersion)
    problems.push_back({path, path + ": format " + std::to_string(file->format_version()) +
                                  " carries no checksums; `tactile upgrade` rewrites it"});
  else
    check_structure(path, problems);
  for (const StreamInfo& stream : file->streams()) verify_stream(*file, stream, problems);
  if (spans != nullptr) note_recording_span(*file, *spans);
  return problems;
}

std::vector<FileProblem> verify_label_store(const std::string& path, const RecordingSpans& spans) {
  std::vector<FileProblem> problems;
  try {
    const LabelStore store(path, LabelStore::OpenMode::kReadOnly);
    for (const StoreProblem& problem : store.check())
      problems.push_back({path, problem.where(path) + ": " + problem.what});
    for (const Label& label : store.list()) {
      const auto span = spans.find(label.recording);
      if (span == spans.end()) continue;
      // Half a millisecond of slack for times written as decimal text elsewhere.
      const double slack = 5e-4;
      if (label.t0 < span->second.first - slack || label.t1 > span->second.second + slack)
        problems.push_back({path, path + ": labels row " + std::to_string(label.id) + ": [" +
                                      number(label.t0) + ", " + number(label.t1) +
                                      "] s lies outside recording " + label.recording + " [" +
                                      number(span->second.first) + ", " +
                                      number(span->second.second) + "] s"});
    }
  } catch (const Error& error) {
    problems.push_back({path, error.what()});
  }
  return problems;
}

VerifyPlan verify_plan(const std::vector<std::string>& paths) {
  std::vector<std::string> files;
  VerifyPlan plan;
  for (const std::string& path : paths) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
      std::vector<std::string> found;
      for (auto it = std::filesystem::recursive_directory_iterator(path, error);
           !error && it != std::filesystem::recursive_directory_iterator(); it.increment(error))
        if (it->is_regular_file() &&
            has_extension(it->path().string(), {".h5", ".hdf5", ".db", ".sqlite", ".sqlite3"}))
          found.push_back(it->path().string());
      if (error)
        plan.walk_problems.push_back({path, path + ": cannot list folder: " + error.message()});
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (!std::filesystem::exists(path, error)) {
      plan.walk_problems.push_back({path, path + ": no such file or folder"});
    } else {
      files.push_back(path);
    }
  }
  // Recordings first: their spans check the labels.
  std::vector<FileKind> kinds;
  for (const std::string& path : files) kinds.push_back(file_kind(path));
  for (const bool recordings : {true, false})
    for (size_t k = 0; k < files.size(); ++k)
      if ((kinds[k] == FileKind::kRecording) == recordings) {
        plan.files.push_back(files[k]);
        plan.kinds.push_back(kinds[k]);
      }
  return plan;
}

std::vector<VerifiedItem> verify_items(const VerifyPlan& plan, const Shard& shard,
                                       const std::function<void(double)>& step) {
  const std::vector<size_t> owned = shard.items_of(plan.files.size());
  // Each recording's span by its place in the plan, gathered in plan order for the label
  // stores (so a recording id given twice ends as in one process: the later file's).
  std::vector<RecordingSpans> noted(plan.files.size());
  RecordingSpans spans;
  bool all_spans = false;
  std::vector<VerifiedItem> items;
  for (const size_t index : owned) {
    if (step) step(static_cast<double>(items.size()) / static_cast<double>(owned.size()));
    const std::string& path = plan.files[index];
    const FileKind kind = plan.kinds[index];
    VerifiedItem item{index, {path, kind, 0}, {}};
    if (kind == FileKind::kRecording) {
      item.problems = verify_recording(path, &noted[index]);
    } else if (kind == FileKind::kLabelStore) {
      if (!all_spans)
        for (size_t other = 0; other < plan.files.size(); ++other) {
          if (plan.kinds[other] != FileKind::kRecording) continue;
          // A recording another shard checks: opened for its span only.
          if (!shard.owns(other)) add_recording_span(plan.files[other], noted[other]);
          for (const auto& [id, span] : noted[other]) spans[id] = span;
        }
      all_spans = true;
      item.problems = verify_label_store(path, spans);
    } else {
      item.problems.push_back({path, path + ": neither a recording nor a label store"});
    }
    item.file.problems = item.problems.size();
    items.push_back(std::move(item));
  }
  return items;
}

VerifyReport verify_report(const VerifyPlan& plan, const std::vector<VerifiedItem>& items) {
  VerifyReport report;
  report.problems = plan.walk_problems;
  for (const VerifiedItem& item : items) {
    report.files.push_back(item.file);
    report.problems.insert(report.problems.end(), item.problems.begin(), item.problems.end());
  }
  return report;
}

VerifyReport verify_paths(const std::vector<std::string>& paths,
                          const std::function<void(double)>& step) {
  const VerifyPlan plan = verify_plan(paths);
  return verify_report(plan, verify_items(plan, {}, step));
}

FileKind parse_file_kind(const std::string& name) {
  for (const FileKind kind : {FileKind::kRecording, FileKind::kLabelStore, FileKind::kUnknown})
    if (name == file_kind_name(kind)) return kind;
  throw Error(name, "not a kind of file verify knows (recording, labels, unknown)");
}

const char* file_kind_name(FileKind kind) {
  switch (kind) {
    case FileKind::kRecording:
      return "recording";
    case FileKind::kLabelStore:
      return "labels";
    case FileKind::kUnknown:
      break;
  }
  return "unknown";
}

std::string verify_summary_line(const VerifyReport& report) {
  size_t recordings = 0, stores = 0;
  for (const VerifiedFile& file : report.files) {
    recordings += file.kind == FileKind::kRecording;
    stores += file.kind == FileKind::kLabelStore;
  }
  return "verified " + std::to_string(recordings) + " recording(s) and " + std::to_string(stores) +
         " label store(s): " +
         (report.problems.empty() ? "no problems"
                                  : std::to_string(report.problems.size()) + " problem(s)");
}

std::string verify_report_json(const VerifyReport& report) {
  nlohmann::json files = nlohmann::json::array();
  for (const VerifiedFile& file : report.files)
    files.push_back(
        {{"path", file.path}, {"kind", file_kind_name(file.kind)}, {"problems", file.problems}});
  nlohmann::json problems = nlohmann::json::array();
  for (const FileProblem& problem : report.problems)
    problems.push_back({{"file", problem.file}, {"problem", problem.message}});
  return nlohmann::json{{"files", files}, {"problems", problems}, {"ok", report.problems.empty()}}
             .dump(2) +
         "\n";
}

namespace {

bool same_recording(const Recording& left, const Recording& right) {
  if (left.id != right.id || left.layout_id != right.layout_id || left.metadata != right.metadata ||
      left.streams.size() != right.streams.size())
    return false;
  for (size_t index = 0; index < left.streams.size(); ++index) {
    const Stream& a = left.streams[index];
    const Stream& b = right.streams[index];
    if (a.name != b.name || a.rate_hz != b.rate_hz || a.start_time != b.start_time ||
        a.channels != b.channels || a.timestamps != b.timestamps ||
        a.samples.rows() != b.samples.rows() || a.samples.cols() != b.samples.cols() ||
        std::memcmp(a.samples.data(), b.samples.data(), sizeof(float) * a.samples.size()) != 0)
      return false;
    const std::vector<std::string> empty_units(a.channels.size());
    if ((a.units.empty() ? empty_units : a.units) != (b.units.empty() ? empty_units : b.units))
      return false;
  }
  return true;
}

}  // namespace

UpgradeResult upgrade_file(const std::string& path) {
  UpgradeResult result;
  result.kind = file_kind(path);
  if (result.kind == FileKind::kLabelStore) {
    const int64_t version = store_version(path);
    if (version < 1) throw Error(path, "not a label store this program can read");
    const LabelStore store(path, LabelStore::OpenMode::kExisting);  // upgrades schema 1
    result.from_version = static_cast<int>(store.opened_version());
    result.to_version = static_cast<int>(store_version(path));
    return result;
  }
  if (result.kind != FileKind::kRecording)
    throw Error(path, "neither a recording nor a label store");
  Recording recording;
  {
    const RecordingFile file(path);
    result.from_version = file.format_version();
    result.to_version = kRecordingFormatVersion;
    if (!result.rewritten()) return result;
    recording = file.read_all();
  }
  // The original stays until the rewritten file has been verified and read back the same.
  write_file_atomically(
      path,
      [&](const std::string& upgraded) {
        write_recording(upgraded, recording);
        const std::vector<FileProblem> problems = verify_recording(upgraded);
        if (!problems.empty())
          throw Error(path, "the rewritten file failed verification (" + problems.front().message +
                                "); the original is unchanged");
        if (!same_recording(read_recording(upgraded), recording))
          throw Error(path, "the rewritten file reads back different; the original is unchanged");
      },
      "original");
  return result;
}

std::string upgrade_line(const std::string& path, const UpgradeResult& result) {
  const std::string what = result.kind == FileKind::kRecording ? "format" : "schema";
  if (result.rewritten())
    return path + ": " + what + " " + std::to_string(result.from_version) + " -> " +
           std::to_string(result.to_version);
  return path + ": already " + what + " " + std::to_string(result.to_version);
}

}  // namespace tactile
