#include "tactile/video/attachments.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/text.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

constexpr int kAttachmentsFormat = 1;

fs::path recording_folder(const std::string& recording_path) {
  return fs::absolute(fs::path(recording_path)).lexically_normal().parent_path();
}

// The checks every attachment passes, read or written; "" when it passes.
std::string attachment_problem(const VideoAttachment& attachment) {
  if (!valid_attachment_name(attachment.name))
    return "the name " + in_quotes(attachment.name) +
           " may hold only letters, digits, '-', '_' and '.'";
  if (attachment.path.empty()) return "the path is empty";
  if (!std::isfinite(attachment.offset)) return "the offset is not a finite number";
  if (!(attachment.rate > 0) || !std::isfinite(attachment.rate))
    return "the rate must be a positive number, not " + shortest_text(attachment.rate);
  return "";
}

}  // namespace

bool valid_attachment_name(const std::string& name) {
  if (name.empty()) return false;
  for (unsigned char c : name)
    if (!std::isalnum(c) && c != '-' && c != '_' && c != '.') return false;
  return true;
}

std::string attachments_path(const std::string& recording_path) {
  return recording_path + ".videos.json";
}

std::vector<VideoAttachment> read_attachments(const std::string& recording_path) {
  const std::string path = attachments_path(recording_path);
  std::error_code error;
  if (!fs::exists(path, error)) return {};
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot read the file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const nlohmann::json document = nlohmann::json::parse(text, nullptr, false);
  if (document.is_discarded()) throw Error(path, "not valid JSON");
  if (!document.is_object()) throw Error(path, "not a JSON object");
  if (!document.contains("format") || !document["format"].is_number_integer())
    throw Error(path, "\"format\" is missing or not a whole number");
  if (document["format"].get<int>() != kAttachmentsFormat)
    throw Error(path, "format " + document["format"].dump() + " is not one this program reads (" +
                          std::to_string(kAttachmentsFormat) + ")");
  if (!document.contains("videos") || !document["videos"].is_array())
    throw Error(path, "\"videos\" is missing or not a list");

  std::vector<VideoAttachment> attachments;
  std::set<std::string> names;
  int number = 0;
  for (const nlohmann::json& entry : document["videos"]) {
    ++number;
    const auto refuse = [&](const std::string& message) {
      throw Error(path, "entry " + std::to_string(number) + ": " + message);
    };
    if (!entry.is_object()) refuse("not a JSON object");
    VideoAttachment attachment;
    for (const char* key : {"name", "path"}) {
      if (!entry.contains(key)) refuse(std::string(key) + " is missing");
      if (!entry[key].is_string()) refuse(std::string(key) + " is not a string");
    }
    attachment.name = entry["name"].get<std::string>();
    attachment.path = entry["path"].get<std::string>();
    for (const char* key : {"offset", "rate"}) {
      if (!entry.contains(key)) continue;  // the defaults: 0 and 1
      if (!entry[key].is_number()) refuse(std::string(key) + " is not a number");
    }
    if (entry.contains("offset")) attachment.offset = entry["offset"].get<double>();
    if (entry.contains("rate")) attachment.rate = entry["rate"].get<double>();
    const std::string problem = attachment_problem(attachment);
    if (!problem.empty()) refuse(problem);
    if (!names.insert(attachment.name).second)
      refuse("the name " + in_quotes(attachment.name) + " is taken by an earlier entry");
    attachments.push_back(attachment);
  }
  return attachments;
}

void write_attachments(const std::string& recording_path,
                       const std::vector<VideoAttachment>& attachments) {
  const std::string path = attachments_path(recording_path);
  nlohmann::json videos = nlohmann::json::array();
  std::set<std::string> names;
  for (const VideoAttachment& attachment : attachments) {
    const std::string problem = attachment_problem(attachment);
    if (!problem.empty()) throw Error(path, "video " + in_quotes(attachment.name) + ": " + problem);
    if (!names.insert(attachment.name).second)
      throw Error(path, "two videos are named " + in_quotes(attachment.name));
    videos.push_back({{"name", attachment.name},
                      {"path", attachment.path},
                      {"offset", attachment.offset},
                      {"rate", attachment.rate}});
  }
  if (attachments.empty()) {
    std::error_code error;
    fs::remove(path, error);
    if (error) throw Error(path, "cannot remove the file: " + error.message());
    return;
  }
  const nlohmann::json document = {{"format", kAttachmentsFormat}, {"videos", videos}};
  write_file_atomically(path, document.dump(2) + "\n", "video attachments");
}

std::string video_path(const std::string& recording_path, const VideoAttachment& attachment) {
  const fs::path kept(attachment.path);
  if (kept.is_absolute()) return kept.lexically_normal().string();
  return (recording_folder(recording_path) / kept).lexically_normal().string();
}

std::string kept_video_path(const std::string& recording_path, const std::string& video) {
  const fs::path folder = recording_folder(recording_path);
  const fs::path absolute = fs::absolute(fs::path(video)).lexically_normal();
  const fs::path relative = absolute.lexically_relative(folder);
  const bool inside = !relative.empty() && *relative.begin() != "..";
  return inside ? relative.string() : absolute.string();
}

void sync_from_two_points(VideoAttachment& attachment, double r1, double v1, double r2, double v2) {
  if (!std::isfinite(r1) || !std::isfinite(r2) || !std::isfinite(v1) || !std::isfinite(v2))
    throw Error("video sync", "the two points' times must be finite numbers");
  if (r1 == r2)
    throw Error("video sync", "the two points are at the same recording time (" + seconds_text(r1) +
                                  " s): they cannot give a rate");
  const double rate = (v2 - v1) / (r2 - r1);
  if (!(rate > 0))
    throw Error("video sync", "the two points give a rate of " + significant_text(rate, 4) +
                                  " video seconds per recording second: the video would run "
                                  "backwards or stand still; are the points swapped?");
  attachment.rate = rate;
  attachment.offset = r1 - v1 / rate;
}

const VideoAttachment* find_attachment(const std::vector<VideoAttachment>& attachments,
                                       const std::string& name) {
  for (const VideoAttachment& attachment : attachments)
    if (attachment.name == name) return &attachment;
  return nullptr;
}

size_t attachment_index(const std::vector<VideoAttachment>& attachments, const std::string& name,
                        const std::string& recording_path) {
  std::vector<std::string> names;
  for (size_t index = 0; index < attachments.size(); ++index) {
    if (attachments[index].name == name) return index;
    names.push_back(attachments[index].name);
  }
  throw Error(recording_path, "no video named " + in_quotes(name) + " is attached (attached: " +
                                  (names.empty() ? "none" : joined(names)) + ")");
}

std::string free_attachment_name(const std::vector<VideoAttachment>& attachments,
                                 const std::string& video) {
  std::string stem = fs::path(video).stem().string();
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '-';
  if (stem.empty()) stem = "video";
  if (!find_attachment(attachments, stem)) return stem;
  for (int suffix = 2;; ++suffix) {
    const std::string name = stem + "-" + std::to_string(suffix);
    if (!find_attachment(attachments, name)) return name;
  }
}

}  // namespace tactile
