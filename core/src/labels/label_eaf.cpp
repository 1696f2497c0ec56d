// ELAN's .eaf (EAF 3.0) both ways: a tier per lane, the classes as a controlled vocabulary,
// region, confidence and note as Symbolic_Association dependent tiers (elan_and_label_studio.h).
#include <tinyxml2.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>

#include "tactile/error.h"
#include "tactile/labels/elan_and_label_studio.h"
#include "tactile/labels/label_format.h"
#include "tactile/labels/lanes.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// EAF's TIME_VALUE is an xsd:unsignedInt of milliseconds (about 49 days). Labels on absolute
// time (a Unix clock) are written relative to an origin kept in a header property.
constexpr double kEafMaxMilliseconds = 4294967295.0;
constexpr const char* kEafRecordingProperty = "tactile:recording";
constexpr const char* kEafOriginProperty = "tactile:time-origin";
constexpr const char* kEafClassType = "tactile-class";
constexpr const char* kEafAttributeType = "tactile-attribute";
constexpr const char* kEafVocabulary = "tactile-classes";

const char* eaf_attribute_or(const tinyxml2::XMLElement* element, const char* name,
                             const char* fallback = "") {
  const char* value = element->Attribute(name);
  return value ? value : fallback;
}

// "a17", the next annotation's id. (Built by insert: GCC 12 warns falsely (-Wrestrict) on
// "a" + std::to_string(...).)
std::string eaf_annotation_id(int64_t& next_annotation) {
  std::string id = std::to_string(next_annotation++);
  id.insert(id.begin(), 'a');
  return id;
}

// A dependent tier's values by the id of the annotation they refer to.
using EafAttributeValues = std::map<std::string, std::string>;

void eaf_add_dependent_tier(tinyxml2::XMLDocument& document, tinyxml2::XMLElement* root,
                            const std::string& parent, const std::string& kind,
                            const std::vector<std::pair<std::string, std::string>>& values,
                            int64_t& next_annotation) {
  if (values.empty()) return;
  tinyxml2::XMLElement* tier = root->InsertNewChildElement("TIER");
  tier->SetAttribute("LINGUISTIC_TYPE_REF", kEafAttributeType);
  tier->SetAttribute("PARENT_REF", parent.c_str());
  tier->SetAttribute("TIER_ID", (parent + "/" + kind).c_str());
  for (const auto& [reference, value] : values) {
    tinyxml2::XMLElement* annotation =
        tier->InsertNewChildElement("ANNOTATION")->InsertNewChildElement("REF_ANNOTATION");
    annotation->SetAttribute("ANNOTATION_ID", eaf_annotation_id(next_annotation).c_str());
    annotation->SetAttribute("ANNOTATION_REF", reference.c_str());
    annotation->InsertNewChildElement("ANNOTATION_VALUE")->SetText(value.c_str());
  }
  (void)document;
}

// A time slot's value in seconds; unaligned slots (no TIME_VALUE) are absent.
struct EafSlots {
  std::map<std::string, std::optional<int64_t>> milliseconds;
};

EafSlots eaf_time_slots(const tinyxml2::XMLElement* root, const std::string& where) {
  EafSlots slots;
  const tinyxml2::XMLElement* order = root->FirstChildElement("TIME_ORDER");
  if (!order) return slots;
  for (const tinyxml2::XMLElement* slot = order->FirstChildElement("TIME_SLOT"); slot;
       slot = slot->NextSiblingElement("TIME_SLOT")) {
    const std::string id = eaf_attribute_or(slot, "TIME_SLOT_ID");
    const std::string at =
        where + " time slot '" + id + "' (line " + std::to_string(slot->GetLineNum()) + ")";
    if (id.empty()) throw Error(at, "a TIME_SLOT without TIME_SLOT_ID");
    if (slots.milliseconds.count(id)) throw Error(at, "a second time slot with this id");
    const char* value = slot->Attribute("TIME_VALUE");
    if (!value) {
      slots.milliseconds[id] = std::nullopt;
      continue;
    }
    errno = 0;
    char* end = nullptr;
    const long long number = std::strtoll(value, &end, 10);
    if (end == value || *end != '\0' || errno == ERANGE || number < 0 ||
        static_cast<double>(number) > kEafMaxMilliseconds)
      throw Error(at, std::string("TIME_VALUE '") + value +
                          "' is not a whole number of milliseconds in 0..4294967295");
    slots.milliseconds[id] = number;
  }
  return slots;
}

std::string eaf_recording_from_header(const tinyxml2::XMLElement* root, double& origin,
                                      const std::string& where) {
  std::string recording;
  const tinyxml2::XMLElement* header = root->FirstChildElement("HEADER");
  if (!header) return recording;
  for (const tinyxml2::XMLElement* property = header->FirstChildElement("PROPERTY"); property;
       property = property->NextSiblingElement("PROPERTY")) {
    const std::string name = eaf_attribute_or(property, "NAME");
    const char* text = property->GetText();
    if (name == kEafRecordingProperty && text) recording = text;
    if (name == kEafOriginProperty && text) {
      char* end = nullptr;
      origin = std::strtod(text, &end);
      if (end == text || *end != '\0' || !std::isfinite(origin))
        throw Error(where + " property " + kEafOriginProperty,
                    std::string("'") + text + "' is not a time in seconds");
    }
  }
  if (!recording.empty()) return recording;
  // Else the media file's name without folder and extension.
  if (const tinyxml2::XMLElement* media = header->FirstChildElement("MEDIA_DESCRIPTOR")) {
    std::string url =
        eaf_attribute_or(media, "RELATIVE_MEDIA_URL", eaf_attribute_or(media, "MEDIA_URL"));
    if (url.empty()) url = eaf_attribute_or(media, "MEDIA_URL");
    const size_t slash = url.find_last_of('/');
    if (slash != std::string::npos) url = url.substr(slash + 1);
    const size_t dot = url.find_last_of('.');
    if (dot != std::string::npos && dot > 0) url = url.substr(0, dot);
    recording = url;
  }
  return recording;
}

// A tier's lane unless mapped: the tier id when it names a lane ("ground-truth", "manual:ana"),
// else the tier's ANNOTATOR, else the tier id as a person's name.
std::string eaf_default_lane(const std::string& id, const std::string& annotator) {
  if (id != "ground-truth" && id.find(':') == std::string::npos && !annotator.empty())
    return annotator;
  return id;
}

const tinyxml2::XMLElement* eaf_root(tinyxml2::XMLDocument& document, const std::string& text,
                                     const std::string& where) {
  if (document.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS)
    throw Error(where + ":" + std::to_string(document.ErrorLineNum()),
                std::string("not XML: ") + document.ErrorStr());
  const tinyxml2::XMLElement* root = document.RootElement();
  if (!root || std::string(root->Name()) != "ANNOTATION_DOCUMENT")
    throw Error(where, "expected an ELAN document (ANNOTATION_DOCUMENT)");
  return root;
}

}  // namespace

InteropSources eaf_sources(const std::string& text, const std::string& where) {
  tinyxml2::XMLDocument document;
  const tinyxml2::XMLElement* root = eaf_root(document, text, where);
  InteropSources sources;
  sources.format = "ELAN";
  double origin = 0.0;
  sources.recording = eaf_recording_from_header(root, origin, where);
  for (const tinyxml2::XMLElement* tier = root->FirstChildElement("TIER"); tier;
       tier = tier->NextSiblingElement("TIER")) {
    if (tier->Attribute("PARENT_REF")) continue;  // regions, confidences, notes
    InteropSource source;
    source.name = eaf_attribute_or(tier, "TIER_ID");
    source.lane = eaf_default_lane(source.name, eaf_attribute_or(tier, "ANNOTATOR"));
    for (const tinyxml2::XMLElement* annotation = tier->FirstChildElement("ANNOTATION"); annotation;
         annotation = annotation->NextSiblingElement("ANNOTATION"))
      ++source.labels;
    sources.sources.push_back(std::move(source));
  }
  return sources;
}

std::string read_interop_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw Error(path, "cannot read the file");
  const std::streamoff size = in.tellg();
  constexpr std::streamoff kLimit = std::streamoff(256) << 20;
  if (size < 0) throw Error(path, "cannot tell the file's size");
  if (size > kLimit) throw Error(path, "larger than 256 MiB: not a label file");
  std::string text(static_cast<size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(text.data(), size)) throw Error(path, "cannot read the file");
  return text;
}

std::string labels_eaf(const std::vector<Label>& labels,
                       const std::vector<std::string>& vocabulary) {
  std::string recording;
  double earliest = 0.0, latest = 0.0;
  for (const Label& label : labels) {
    if (recording.empty()) recording = label.recording;
    if (label.recording != recording)
      throw Error("ELAN export", "labels of recordings '" + recording + "' and '" +
                                     label.recording + "': one .eaf holds one recording");
    earliest = std::min(earliest, label.t0);
    latest = std::max(latest, label.t1);
  }
  // Times from 0 when they fit ELAN's range, else from the first label's whole second.
  double origin = 0.0;
  if (earliest < 0.0 || latest * 1000.0 > kEafMaxMilliseconds) {
    origin = labels.empty() ? 0.0 : labels.front().t0;
    for (const Label& label : labels) origin = std::min(origin, label.t0);
    origin = std::floor(origin);
  }

  tinyxml2::XMLDocument document;
  document.InsertFirstChild(document.NewDeclaration("xml version=\"1.0\" encoding=\"UTF-8\""));
  tinyxml2::XMLElement* root = document.NewElement("ANNOTATION_DOCUMENT");
  document.InsertEndChild(root);
  root->SetAttribute("AUTHOR", "tactile");
  root->SetAttribute("DATE", "1970-01-01T00:00:00Z");
  root->SetAttribute("FORMAT", "3.0");
  root->SetAttribute("VERSION", "3.0");
  root->SetAttribute("xmlns:xsi", "http://www.w3.org/2001/XMLSchema-instance");
  root->SetAttribute("xsi:noNamespaceSchemaLocation", "http://www.mpi.nl/tools/elan/EAFv3.0.xsd");
  tinyxml2::XMLElement* header = root->InsertNewChildElement("HEADER");
  header->SetAttribute("MEDIA_FILE", "");
  header->SetAttribute("TIME_UNITS", "milliseconds");
  // ELAN plays media, not our recordings: the media descriptor names the CSV that
  // `tactile export csv` writes beside it, so the user can link a video or audio instead.
  tinyxml2::XMLElement* media = header->InsertNewChildElement("MEDIA_DESCRIPTOR");
  media->SetAttribute("MEDIA_URL", ("file:///" + recording + ".csv").c_str());
  media->SetAttribute("MIME_TYPE", "text/plain");
  media->SetAttribute("RELATIVE_MEDIA_URL", ("./" + recording + ".csv").c_str());
  tinyxml2::XMLElement* property = header->InsertNewChildElement("PROPERTY");
  property->SetAttribute("NAME", kEafRecordingProperty);
  property->SetText(recording.c_str());
  if (origin != 0.0) {
    property = header->InsertNewChildElement("PROPERTY");
    property->SetAttribute("NAME", kEafOriginProperty);
    property->SetText(shortest_text(origin).c_str());
  }

  // Time slots: one per distinct millisecond, in order.
  auto milliseconds = [&](double t) { return std::llround((t - origin) * 1000.0); };
  std::set<long long> times;
  for (const Label& label : labels) {
    const long long t0 = milliseconds(label.t0), t1 = milliseconds(label.t1);
    if (t1 <= t0)
      throw Error("ELAN export label " + std::to_string(label.id),
                  "spans less than a millisecond (" + shortest_text(label.t0) + "-" +
                      shortest_text(label.t1) + " s): ELAN counts whole milliseconds");
    times.insert(t0);
    times.insert(t1);
  }
  std::map<long long, std::string> slot_of;
  tinyxml2::XMLElement* order = root->InsertNewChildElement("TIME_ORDER");
  for (long long t : times) {
    const std::string id = "ts" + std::to_string(slot_of.size() + 1);
    slot_of[t] = id;
    tinyxml2::XMLElement* slot = order->InsertNewChildElement("TIME_SLOT");
    slot->SetAttribute("TIME_SLOT_ID", id.c_str());
    slot->SetAttribute("TIME_VALUE", static_cast<int64_t>(t));
  }

  // A tier per lane, in the lanes' order, and its dependent tiers.
  int64_t next_annotation = 1;
  const Lanes lanes = group_into_lanes(labels);
  for (size_t k = 0; k < lanes.keys.size(); ++k) {
    const std::string tier_id = lanes.keys[k].id();
    tinyxml2::XMLElement* tier = root->InsertNewChildElement("TIER");
    tier->SetAttribute("LINGUISTIC_TYPE_REF", kEafClassType);
    tier->SetAttribute("TIER_ID", tier_id.c_str());
    const std::vector<Label>& members = lanes.lanes[k].labels();
    if (!members.empty()) tier->SetAttribute("ANNOTATOR", members.front().annotator.c_str());
    std::vector<std::pair<std::string, std::string>> regions, confidences, notes;
    for (const Label& label : members) {
      const std::string id = eaf_annotation_id(next_annotation);
      tinyxml2::XMLElement* annotation =
          tier->InsertNewChildElement("ANNOTATION")->InsertNewChildElement("ALIGNABLE_ANNOTATION");
      annotation->SetAttribute("ANNOTATION_ID", id.c_str());
      annotation->SetAttribute("TIME_SLOT_REF1", slot_of[milliseconds(label.t0)].c_str());
      annotation->SetAttribute("TIME_SLOT_REF2", slot_of[milliseconds(label.t1)].c_str());
      annotation->InsertNewChildElement("ANNOTATION_VALUE")->SetText(label.class_name.c_str());
      if (label.region != "all") regions.emplace_back(id, label.region);
      if (label.confidence != 1.0) confidences.emplace_back(id, shortest_text(label.confidence));
      if (!label.note.empty()) notes.emplace_back(id, label.note);
    }
    eaf_add_dependent_tier(document, root, tier_id, "region", regions, next_annotation);
    eaf_add_dependent_tier(document, root, tier_id, "confidence", confidences, next_annotation);
    eaf_add_dependent_tier(document, root, tier_id, "note", notes, next_annotation);
  }
  property = header->InsertNewChildElement("PROPERTY");
  property->SetAttribute("NAME", "lastUsedAnnotationId");
  property->SetText(static_cast<int64_t>(next_annotation - 1));

  tinyxml2::XMLElement* type = root->InsertNewChildElement("LINGUISTIC_TYPE");
  type->SetAttribute("CONTROLLED_VOCABULARY_REF", kEafVocabulary);
  type->SetAttribute("GRAPHIC_REFERENCES", "false");
  type->SetAttribute("LINGUISTIC_TYPE_ID", kEafClassType);
  type->SetAttribute("TIME_ALIGNABLE", "true");
  type = root->InsertNewChildElement("LINGUISTIC_TYPE");
  type->SetAttribute("CONSTRAINTS", "Symbolic_Association");
  type->SetAttribute("GRAPHIC_REFERENCES", "false");
  type->SetAttribute("LINGUISTIC_TYPE_ID", kEafAttributeType);
  type->SetAttribute("TIME_ALIGNABLE", "false");
  tinyxml2::XMLElement* language = root->InsertNewChildElement("LANGUAGE");
  language->SetAttribute("LANG_DEF", "http://cdb.iso.org/lg/CDB-00130975-001");
  language->SetAttribute("LANG_ID", "eng");
  language->SetAttribute("LANG_LABEL", "English (eng)");
  for (const auto& [stereotype, description] :
       {std::pair{"Time_Subdivision",
                  "Time subdivision of parent annotation's time interval, no time gaps allowed "
                  "within this interval"},
        std::pair{"Symbolic_Subdivision",
                  "Symbolic subdivision of a parent annotation. Annotations refering to the same "
                  "parent are ordered"},
        std::pair{"Symbolic_Association", "1-1 association with a parent annotation"},
        std::pair{"Included_In",
                  "Time alignable annotations within the parent annotation's time interval, "
                  "gaps are allowed"}}) {
    tinyxml2::XMLElement* constraint = root->InsertNewChildElement("CONSTRAINT");
    constraint->SetAttribute("DESCRIPTION", description);
    constraint->SetAttribute("STEREOTYPE", stereotype);
  }
  // The vocabulary: the skin's classes, then any others the labels use.
  std::vector<std::string> classes = vocabulary;
  for (const Label& label : labels)
    if (std::find(classes.begin(), classes.end(), label.class_name) == classes.end())
      classes.push_back(label.class_name);
  tinyxml2::XMLElement* cv = root->InsertNewChildElement("CONTROLLED_VOCABULARY");
  cv->SetAttribute("CV_ID", kEafVocabulary);
  tinyxml2::XMLElement* description = cv->InsertNewChildElement("DESCRIPTION");
  description->SetAttribute("LANG_REF", "eng");
  description->SetText("Touch classes");
  for (size_t k = 0; k < classes.size(); ++k) {
    tinyxml2::XMLElement* entry = cv->InsertNewChildElement("CV_ENTRY_ML");
    entry->SetAttribute("CVE_ID", ("cveid" + std::to_string(k + 1)).c_str());
    tinyxml2::XMLElement* value = entry->InsertNewChildElement("CVE_VALUE");
    value->SetAttribute("DESCRIPTION", "");
    value->SetAttribute("LANG_REF", "eng");
    value->SetText(classes[k].c_str());
  }
  tinyxml2::XMLPrinter printer;
  document.Print(&printer);
  return std::string(printer.CStr(), static_cast<size_t>(printer.CStrSize() - 1));
}

std::vector<Label> parse_eaf(const std::string& text, const std::string& where,
                             const InteropImport& options) {
  tinyxml2::XMLDocument document;
  const tinyxml2::XMLElement* root = eaf_root(document, text, where);
  const EafSlots slots = eaf_time_slots(root, where);
  double origin = 0.0;
  std::string recording = eaf_recording_from_header(root, origin, where);
  if (!options.recording.empty()) recording = options.recording;
  if (recording.empty())
    throw Error(where,
                "the file names no recording (no tactile:recording property, no media): "
                "give --recording");

  // Tiers by id; dependent tiers' values by parent tier.
  struct Tier {
    const tinyxml2::XMLElement* element = nullptr;
    std::string parent, annotator;
  };
  std::map<std::string, Tier> tiers;
  std::vector<std::string> tier_order;
  for (const tinyxml2::XMLElement* tier = root->FirstChildElement("TIER"); tier;
       tier = tier->NextSiblingElement("TIER")) {
    const std::string id = eaf_attribute_or(tier, "TIER_ID");
    if (id.empty())
      throw Error(where + ":" + std::to_string(tier->GetLineNum()), "a TIER without TIER_ID");
    if (tiers.count(id)) throw Error(where + " tier '" + id + "'", "a second tier with this id");
    tiers[id] = {tier, eaf_attribute_or(tier, "PARENT_REF"), eaf_attribute_or(tier, "ANNOTATOR")};
    tier_order.push_back(id);
  }
  for (const auto& [name, lane] : options.tiers)
    if (!tiers.count(name)) throw Error(where, "no tier named '" + name + "' (--tier)");

  // Values of the dependent (REF_ANNOTATION) tiers: by kind, then by parent annotation id.
  std::map<std::string, EafAttributeValues> regions, confidences, notes;
  for (const std::string& id : tier_order) {
    const Tier& tier = tiers[id];
    if (tier.parent.empty() || options.tiers.count(id)) continue;
    const std::string kind =
        id.starts_with(tier.parent + "/") ? id.substr(tier.parent.size() + 1) : std::string();
    for (const tinyxml2::XMLElement* annotation = tier.element->FirstChildElement("ANNOTATION");
         annotation; annotation = annotation->NextSiblingElement("ANNOTATION")) {
      const tinyxml2::XMLElement* reference = annotation->FirstChildElement("REF_ANNOTATION");
      if (!reference) continue;
      const std::string target = eaf_attribute_or(reference, "ANNOTATION_REF");
      const tinyxml2::XMLElement* value_element = reference->FirstChildElement("ANNOTATION_VALUE");
      const char* value_text = value_element ? value_element->GetText() : nullptr;
      const std::string value = value_text ? value_text : "";
      if (kind == "region")
        regions[tier.parent][target] = value;
      else if (kind == "confidence")
        confidences[tier.parent][target] = value;
      else if (!value.empty()) {
        // Any other dependent tier is a note ELAN users wrote; several are kept one per line.
        std::string& note = notes[tier.parent][target];
        note += (note.empty() ? "" : "\n") + value;
      }
    }
  }

  std::vector<Label> labels;
  for (const std::string& id : tier_order) {
    const Tier& tier = tiers[id];
    const bool chosen = options.tiers.empty() ? tier.parent.empty() : options.tiers.count(id) > 0;
    if (!chosen) continue;
    // The lane: the option's, else the tier id when it names a lane, else the tier's annotator.
    std::string lane_id = options.tiers.count(id) ? options.tiers.at(id) : std::string();
    if (lane_id.empty()) lane_id = eaf_default_lane(id, tier.annotator);
    const LaneKey lane = lane_from_id(lane_id);
    for (const tinyxml2::XMLElement* annotation = tier.element->FirstChildElement("ANNOTATION");
         annotation; annotation = annotation->NextSiblingElement("ANNOTATION")) {
      const tinyxml2::XMLElement* aligned = annotation->FirstChildElement("ALIGNABLE_ANNOTATION");
      if (!aligned) {
        const tinyxml2::XMLElement* reference = annotation->FirstChildElement("REF_ANNOTATION");
        throw Error(where + " tier '" + id + "' annotation '" +
                        (reference ? eaf_attribute_or(reference, "ANNOTATION_ID") : "") + "'",
                    "not time-aligned (a reference annotation): a label needs a start and an end");
      }
      const std::string annotation_id = eaf_attribute_or(aligned, "ANNOTATION_ID");
      const std::string at = where + " tier '" + id + "' annotation '" + annotation_id + "'";
      std::optional<int64_t> ends[2];
      for (int k = 0; k < 2; ++k) {
        const std::string slot =
            eaf_attribute_or(aligned, k == 0 ? "TIME_SLOT_REF1" : "TIME_SLOT_REF2");
        const auto found = slots.milliseconds.find(slot);
        if (found == slots.milliseconds.end())
          throw Error(at, "time slot '" + slot + "' is not in the TIME_ORDER");
        if (!found->second)
          throw Error(
              at, "unaligned: time slot '" + slot + "' has no time value (align it in ELAN first)");
        ends[k] = found->second;
      }
      Label label;
      label.recording = recording;
      label.t0 = origin + static_cast<double>(*ends[0]) / 1000.0;
      label.t1 = origin + static_cast<double>(*ends[1]) / 1000.0;
      if (!(label.t1 > label.t0))
        throw Error(at, "ends at " + shortest_text(label.t1) + " s, not after its start " +
                            shortest_text(label.t0) + " s");
      const tinyxml2::XMLElement* value = aligned->FirstChildElement("ANNOTATION_VALUE");
      const char* class_text = value ? value->GetText() : nullptr;
      label.class_name = class_text ? class_text : "";
      if (label.class_name.empty()) throw Error(at, "an empty value: a label needs a class");
      label.source = lane.source;
      label.annotator = lane.source == LabelSource::kGroundTruth ? tier.annotator : lane.annotator;
      if (lane.source != LabelSource::kGroundTruth && label.annotator.empty())
        throw Error(at, "no annotator for lane '" + lane_id + "'");
      if (const auto tier_regions = regions.find(id); tier_regions != regions.end())
        if (const auto found = tier_regions->second.find(annotation_id);
            found != tier_regions->second.end()) {
          if (found->second.empty()) throw Error(at, "an empty region in tier '" + id + "/region'");
          label.region = found->second;
        }
      if (const auto tier_confidences = confidences.find(id); tier_confidences != confidences.end())
        if (const auto found = tier_confidences->second.find(annotation_id);
            found != tier_confidences->second.end()) {
          char* end = nullptr;
          const double confidence = std::strtod(found->second.c_str(), &end);
          if (found->second.empty() || *end != '\0' || !(confidence >= 0.0 && confidence <= 1.0))
            throw Error(at, "confidence '" + found->second + "' is not a number in [0, 1]");
          label.confidence = confidence;
        }
      if (const auto tier_notes = notes.find(id); tier_notes != notes.end())
        if (const auto found = tier_notes->second.find(annotation_id);
            found != tier_notes->second.end())
          label.note = found->second;
      labels.push_back(std::move(label));
    }
  }
  return labels;
}

//---- The format's row (labels/label_format.h)

namespace {

class ElanFormat : public LabelFormat {
 public:
  std::string name() const override { return "ELAN"; }
  std::string flag() const override { return "--eaf"; }
  std::string description() const override { return "ELAN .eaf (one tier per lane)"; }
  std::string extension() const override { return ".eaf"; }
  bool one_recording() const override { return true; }
  bool reads(const std::string& extension,
             const std::function<const std::string&()>&) const override {
    return extension == ".eaf";
  }
  std::vector<Label> read(const std::string& path, const InteropImport& options,
                          std::vector<std::string>&) const override {
    return parse_eaf(read_interop_text(path), path, options);
  }
  InteropSources sources(const std::string& path) const override {
    return eaf_sources(read_interop_text(path), path);
  }
  // One recording: refused naming --recording and the recordings when the labels hold several.
  std::string write(const std::vector<Label>& labels, const std::vector<std::string>& vocabulary,
                    const InteropExport&) const override {
    std::vector<std::string> recordings;
    for (const Label& label : labels)
      if (std::find(recordings.begin(), recordings.end(), label.recording) == recordings.end())
        recordings.push_back(label.recording);
    if (recordings.size() > 1)
      throw Error("--recording", "one .eaf holds one recording; the labels hold " +
                                     std::to_string(recordings.size()) + " (" + recordings[0] +
                                     ", " + recordings[1] + (recordings.size() > 2 ? ", ..." : "") +
                                     ")");
    return labels_eaf(labels, vocabulary);
  }
};

}  // namespace

std::unique_ptr<LabelFormat> elan_label_format() { return std::make_unique<ElanFormat>(); }

}  // namespace tactile
