#pragma once
// One record per skin: everything the rest of the program needs to know about a skin, in one
// place. Every list of skins in core and in the programs reads the table of records; adding a
// skin is registering one record (its layout, simulator and feature pipeline live in their own
// files) and nothing else changes. The five skins of the papers are registered on first use.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/layout/skin_layout.h"
#include "tactile/sim/simulator.h"

namespace tactile {

//---- How the device sends its samples (docs/PACKETS.md) --------------------------------------

// Physical value = offset + count * step, for counts in [min_count, max_count]. Encoding
// rounds to the nearest count and saturates at the limits, as the device's ADC does.
struct CountScale {
  double offset = 0.0;
  double step = 1.0;
  int32_t min_count = 0;
  int32_t max_count = 0;

  // `value` must be finite; sets `saturated` when it was clamped.
  int32_t to_count(double value, bool& saturated) const;
  float to_value(int32_t count) const;
};

// How one sample's values sit in the payload.
enum class WireWord {
  kInt16,     // one little-endian int16 per value
  kUint16,    // one little-endian uint16 per value
  kPacked12,  // two 12-bit values in 3 bytes
  kNaoCells,  // one 18-byte record per cell (live/packets.h)
};

struct PacketFormat {
  std::string skin;  // filled in from the record when it is registered
  uint8_t code = 0;  // the skin's code in the packet header; unique among the skins
  double rate_hz = 0.0;
  int samples_per_datagram = 1;
  int wire_channels = 0;
  WireWord word = WireWord::kUint16;
  CountScale scale;  // for every value, except nao cells (per modality)
};

//---- Online classification ------------------------------------------------------------------

// How a live stream of the skin is classified (live/online_classifier.h).
struct OnlineOptions {
  std::string segmenter = "adaptive";  // finds the touches in the recent stream
  std::string segmenter_params;        // "key=value,..."
  double window_seconds = 2.0;   // the longest stretch of an open touch a provisional decision sees
  double hop_seconds = 0.1;      // a decision this often
  double release_seconds = 0.1;  // a touch that ended this long ago is over
  double lookback_seconds = 8.0;  // what the segmenter and the pipeline see each hop
};

//---- The record -----------------------------------------------------------------------------

struct SkinRecord {
  std::string id;    // the layout id recordings of this skin carry
  std::string name;  // one line for help texts and menus
  // The layout, with its display hints (display_modality, display range) and its class
  // vocabulary in display order. None: assets/layouts/<id>.json. A layout given here is added
  // to those load_layout finds (add_layout), so every part of the program reads it by id.
  std::optional<SkinLayout> layout;
  TrialGenerator simulate;  // empty when the skin has no simulator
  // Its share of the demo workspace (`tactile simulate --demo`); 0 subjects: not in it.
  int demo_subjects = 0;
  int demo_repetitions = 0;            // gestures per class; 0 = the simulator's default
  std::string pipeline = "generic";    // default feature pipeline
  std::string segmenter = "adaptive";  // default segmenter of a recording
  std::string segmenter_params;
  std::optional<PacketFormat> packet;  // live packets; none: no live input of its own
  OnlineOptions online;
  // The class vocabulary in display order (colours follow it); empty: the layout's.
  std::vector<std::string> classes;
};

// Adds a skin, or replaces the record of the same id. Throws tactile::Error when the id is
// empty or not a plain layout name, or when its packet code is taken by another skin. Register
// at start-up, before other threads read the records: a replaced record changes in place.
void register_skin(SkinRecord record);

// Every registered skin, the papers' five first, then in registration order; for help texts
// and messages, joined(skin_ids()) (tactile/text.h).
std::vector<std::string> skin_ids();
// The skins with a simulator, and those with a live packet format.
std::vector<std::string> simulated_skin_ids();
std::vector<std::string> packet_skin_ids();
// nullptr when no skin has this id. Records stay where they are until the program ends.
const SkinRecord* find_skin(const std::string& id);
// Throws tactile::Error at `where` naming the known skins.
const SkinRecord& skin_record(const std::string& id, const std::string& where = "skin");
// The skin whose packets carry `code`; nullptr for none.
const SkinRecord* find_skin_by_packet_code(uint8_t code);

// The feature pipeline a recording of this layout is described by by default: its skin's,
// "generic" for a layout that is no registered skin.
std::string default_pipeline(const std::string& layout_id);
// The segmenter (and its parameters) to find the touches of such a recording.
std::pair<std::string, std::string> default_segmenter(const std::string& layout_id);
// The class vocabulary in display order: the record's, else the layout's; empty for a
// layout that is no registered skin.
std::vector<std::string> skin_classes(const std::string& layout_id);
// The online defaults of the skin; the general defaults for any other layout.
OnlineOptions default_online_options(const std::string& layout_id);

}  // namespace tactile
