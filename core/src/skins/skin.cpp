#include "tactile/skins/skin.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <mutex>

#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile {

// The papers' five records (builtin_skins.cpp).
std::vector<SkinRecord> builtin_skins();

namespace {

// Records never move once registered (a deque grows at its end), so a pointer handed out
// stays valid while another thread registers a skin. The papers' five are there from the start.
struct SkinTable {
  SkinTable() {
    for (SkinRecord& record : builtin_skins()) {
      if (record.packet) record.packet->skin = record.id;
      records.push_back(std::move(record));
    }
  }
  std::mutex mutex;
  std::deque<SkinRecord> records;
};

SkinTable& table() {
  static SkinTable skins;
  return skins;
}

template <typename Keep>
std::vector<std::string> ids_where(Keep keep) {
  SkinTable& skins = table();
  const std::lock_guard lock(skins.mutex);
  std::vector<std::string> ids;
  for (const SkinRecord& record : skins.records)
    if (keep(record)) ids.push_back(record.id);
  return ids;
}

}  // namespace

int32_t CountScale::to_count(double value, bool& saturated) const {
  const double count = std::round((value - offset) / step);
  if (count < min_count) {
    saturated = true;
    return min_count;
  }
  if (count > max_count) {
    saturated = true;
    return max_count;
  }
  return static_cast<int32_t>(count);
}

float CountScale::to_value(int32_t count) const {
  return static_cast<float>(offset + static_cast<double>(count) * step);
}

void register_skin(SkinRecord record) {
  const std::string where = "skin " + record.id;
  if (record.id.empty() || is_generic_layout_id(record.id))
    throw Error(where, "needs a plain id (letters, digits, '-' and '_')");
  if (record.layout) {
    if (record.layout->id != record.id)
      throw Error(where, "its layout's id is \"" + record.layout->id + "\"");
    add_layout(*record.layout);  // validates it
  }
  if (record.packet) record.packet->skin = record.id;
  SkinTable& skins = table();
  const std::lock_guard lock(skins.mutex);
  for (SkinRecord& known : skins.records) {
    if (record.packet && known.packet && known.id != record.id &&
        known.packet->code == record.packet->code)
      throw Error(where, "packet code " + std::to_string(record.packet->code) + " is skin " +
                             known.id + "'s");
  }
  const auto same = std::find_if(skins.records.begin(), skins.records.end(),
                                 [&](const SkinRecord& known) { return known.id == record.id; });
  if (same != skins.records.end())
    *same = std::move(record);
  else
    skins.records.push_back(std::move(record));
}

std::vector<std::string> skin_ids() {
  return ids_where([](const SkinRecord&) { return true; });
}

std::vector<std::string> simulated_skin_ids() {
  return ids_where([](const SkinRecord& record) { return static_cast<bool>(record.simulate); });
}

std::vector<std::string> packet_skin_ids() {
  return ids_where([](const SkinRecord& record) { return record.packet.has_value(); });
}

const SkinRecord* find_skin(const std::string& id) {
  SkinTable& skins = table();
  const std::lock_guard lock(skins.mutex);
  for (const SkinRecord& record : skins.records)
    if (record.id == id) return &record;
  return nullptr;
}

const SkinRecord& skin_record(const std::string& id, const std::string& where) {
  const SkinRecord* record = find_skin(id);
  if (!record) throw Error(where, "no skin \"" + id + "\" (skins: " + joined(skin_ids()) + ")");
  return *record;
}

const SkinRecord* find_skin_by_packet_code(uint8_t code) {
  SkinTable& skins = table();
  const std::lock_guard lock(skins.mutex);
  for (const SkinRecord& record : skins.records)
    if (record.packet && record.packet->code == code) return &record;
  return nullptr;
}

std::string default_pipeline(const std::string& layout_id) {
  const SkinRecord* record = find_skin(layout_id);
  return record ? record->pipeline : "generic";
}

std::pair<std::string, std::string> default_segmenter(const std::string& layout_id) {
  const SkinRecord* record = find_skin(layout_id);
  if (!record) return {"adaptive", ""};
  return {record->segmenter, record->segmenter_params};
}

std::vector<std::string> skin_classes(const std::string& layout_id) {
  const SkinRecord* record = find_skin(layout_id);
  if (!record) return {};
  if (!record->classes.empty()) return record->classes;
  return record->layout ? record->layout->classes : load_layout(layout_id).classes;
}

OnlineOptions default_online_options(const std::string& layout_id) {
  const SkinRecord* record = find_skin(layout_id);
  return record ? record->online : OnlineOptions{};
}

}  // namespace tactile
