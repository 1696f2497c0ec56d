#include "tactile/segment/nao_window.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <regex>
#include <sstream>
#include <unordered_map>

#include "tactile/dsp/rest_offset.h"
#include "tactile/error.h"

namespace tactile {

//---- Layout and stream lookup

namespace {

// Layout channel index of a taxel's modality slot, or -1.
int slot_channel(const Taxel& taxel, int modality) {
  if (modality < 0 || modality >= static_cast<int>(taxel.channels.size())) return -1;
  return taxel.channels[static_cast<size_t>(modality)];
}

}  // namespace

NaoSkin locate_nao_skin(const Recording& recording, const SkinLayout& layout) {
  const std::string layout_where = "layout " + layout.id;
  const std::array<int, 3> acceleration = {layout.modality_index("ax"), layout.modality_index("ay"),
                                           layout.modality_index("az")};
  const int proximity = layout.modality_index("prox");
  std::vector<int> force;
  static const std::regex force_name("f[0-9]+");
  for (size_t m = 0; m < layout.modalities.size(); ++m)
    if (std::regex_match(layout.modalities[m], force_name)) force.push_back(static_cast<int>(m));
  if (acceleration[0] < 0 || acceleration[1] < 0 || acceleration[2] < 0 || proximity < 0 ||
      force.empty())
    throw Error(layout_where, "needs modalities ax, ay, az, f1.. and prox (a NAO-like skin)");

  NaoSkin skin;
  for (const Group& group : layout.groups) {
    if (group.kind != "side") continue;
    BodyPart part;
    part.id = group.id;
    for (int64_t id : group.taxels) {
      const Taxel* taxel = layout.find_taxel(id);
      if (taxel == nullptr) throw Error(layout_where, "group " + group.id + ": unknown taxel");
      CellColumns cell;
      cell.taxel = id;
      // Layout channel indices for now; mapped to stream columns below.
      for (int axis = 0; axis < 3; ++axis)
        cell.acceleration[axis] = slot_channel(*taxel, acceleration[axis]);
      for (int slot : force) cell.force.push_back(slot_channel(*taxel, slot));
      cell.proximity = slot_channel(*taxel, proximity);
      part.cells.push_back(std::move(cell));
    }
    skin.body_parts.push_back(std::move(part));
  }
  if (skin.body_parts.empty())
    throw Error(layout_where, "has no groups of kind \"side\" (the body parts front and back)");

  // The stream that holds the first cell's proximity channel holds the skin.
  const BodyPart& first_part = skin.body_parts.front();
  if (first_part.cells.empty() || first_part.cells.front().proximity < 0)
    throw Error(layout_where,
                "body part " + first_part.id + " has no cell with a proximity channel");
  const std::string& probe =
      layout.channels[static_cast<size_t>(first_part.cells.front().proximity)].name;
  for (const Stream& stream : recording.streams)
    if (std::find(stream.channels.begin(), stream.channels.end(), probe) != stream.channels.end())
      skin.stream = &stream;
  if (skin.stream == nullptr)
    throw Error("recording " + recording.id,
                "no stream has channel " + probe + " of layout " + layout.id);

  std::unordered_map<std::string, int> columns;
  for (size_t c = 0; c < skin.stream->channels.size(); ++c)
    columns.emplace(skin.stream->channels[c], static_cast<int>(c));
  const auto to_column = [&](int channel, const Taxel& taxel) {
    if (channel < 0)
      throw Error(layout_where,
                  "cell " + taxel.name + " lacks an accelerometer, force or proximity channel");
    const std::string& name = layout.channels[static_cast<size_t>(channel)].name;
    const auto found = columns.find(name);
    if (found == columns.end() || found->second >= skin.stream->channel_count())
      throw Error("recording " + recording.id,
                  "stream " + skin.stream->name + " lacks channel " + name);
    return found->second;
  };
  for (BodyPart& part : skin.body_parts) {
    for (CellColumns& cell : part.cells) {
      const Taxel& taxel = *layout.find_taxel(cell.taxel);
      for (int& column : cell.acceleration) column = to_column(column, taxel);
      for (int& column : cell.force) column = to_column(column, taxel);
      cell.proximity = to_column(cell.proximity, taxel);
    }
  }
  return skin;
}

//---- Action window and dynamic cell selection

bool cell_in_contact(std::span<const float> proximity_mm, double contact_mm) {
  for (float distance : proximity_mm)
    if (distance < contact_mm) return true;  // false for NaN
  return false;
}

std::string find_non_finite(const Stream& stream, std::span<const int> columns, int64_t first,
                            int64_t count) {
  for (int column : columns) {
    const float* values = stream.samples.col(column).data() + first;
    for (int64_t t = 0; t < count; ++t) {
      if (std::isfinite(values[t])) continue;
      std::ostringstream reason;
      reason << "non-finite sample in channel " << stream.channels[static_cast<size_t>(column)]
             << " at t = " << stream.time_of(first + t) << " s";
      return reason.str();
    }
  }
  return {};
}

namespace {

void select_cells(const Stream& stream, const NaoSkin& skin, int index, double contact_mm,
                  ContactWindow& window) {
  const BodyPart& part = skin.body_parts[static_cast<size_t>(index)];
  window.body_part = index;
  window.contact.assign(part.cells.size(), 0);
  window.contacted_cells = 0;
  for (size_t c = 0; c < part.cells.size(); ++c) {
    const float* proximity = stream.samples.col(part.cells[c].proximity).data() + window.first;
    const bool touched = cell_in_contact(
        std::span<const float>(proximity, static_cast<size_t>(window.count)), contact_mm);
    window.contact[c] = touched ? 1 : 0;
    window.contacted_cells += touched ? 1 : 0;
  }
}

}  // namespace

ContactWindow contact_window(const NaoSkin& skin, const Label& segment, double contact_mm,
                             int64_t minimum_samples) {
  ContactWindow window;
  const Stream& stream = *skin.stream;
  const auto [first, last] = sample_range(stream, segment.t0, segment.t1);
  window.first = first;
  window.count = last - first;
  if (window.count < std::max<int64_t>(1, minimum_samples)) {
    window.skip_reason = "segment holds " + std::to_string(window.count) +
                         " samples, the method needs " +
                         std::to_string(std::max<int64_t>(1, minimum_samples));
    return window;
  }

  std::vector<int> candidates;
  for (size_t p = 0; p < skin.body_parts.size(); ++p)
    if (segment.region == "all" || segment.region == skin.body_parts[p].id)
      candidates.push_back(static_cast<int>(p));
  if (candidates.empty()) {
    std::string known;
    for (const BodyPart& part : skin.body_parts) known += part.id + ", ";
    window.skip_reason =
        "region \"" + segment.region + "\" is not a body part (" + known + "or all)";
    return window;
  }
  for (int index : candidates) {
    std::vector<int> proximity;
    for (const CellColumns& cell : skin.body_parts[static_cast<size_t>(index)].cells)
      proximity.push_back(cell.proximity);
    window.skip_reason = find_non_finite(stream, proximity, window.first, window.count);
    if (!window.skip_reason.empty()) return window;
  }

  ContactWindow candidate = window;
  for (int index : candidates) {
    select_cells(stream, skin, index, contact_mm, candidate);
    if (window.body_part < 0 || candidate.contacted_cells > window.contacted_cells)
      window = candidate;
  }
  if (window.contacted_cells == 0) window.skip_reason = "no cell in contact";
  return window;
}

Eigen::VectorXd window_column(const Stream& stream, int column, int64_t first, int64_t count) {
  return stream.samples.col(column).segment(first, count).cast<double>();
}

//---- Force elements (spec §1.10)

Eigen::MatrixXd force_elements(const NaoSkin& skin, const ContactWindow& window,
                               bool contacted_only) {
  const Stream& stream = *skin.stream;
  const BodyPart& part = skin.body_parts[static_cast<size_t>(window.body_part)];
  int64_t elements = 0;
  for (size_t c = 0; c < part.cells.size(); ++c)
    if (!contacted_only || window.contact[c])
      elements += static_cast<int64_t>(part.cells[c].force.size());
  Eigen::MatrixXd force(window.count, elements);
  int64_t e = 0;
  for (size_t c = 0; c < part.cells.size(); ++c) {
    if (contacted_only && !window.contact[c]) continue;
    for (int column : part.cells[c].force)
      force.col(e++) =
          stream.samples.col(column).segment(window.first, window.count).cast<double>();
  }
  return force;
}

Eigen::ArrayXXd contact_elements(const Eigen::MatrixXd& force, double force_threshold) {
  return (force.array() >= force_threshold).cast<double>();
}

double contact_time(const Eigen::MatrixXd& force, double force_threshold, double rate_hz) {
  if (force.cols() == 0 || rate_hz <= 0.0) return 0.0;
  const int64_t samples = (force.array() >= force_threshold).rowwise().any().count();
  return static_cast<double>(samples) / rate_hz;
}

//---- Preprocessing of the baselines

Recording remove_force_rest_offsets(const Recording& recording, const SkinLayout& layout,
                                    double contact_mm) {
  Recording referenced = recording;
  const NaoSkin skin = locate_nao_skin(recording, layout);
  // Same stream in the copy: locate it by position.
  const size_t index = static_cast<size_t>(skin.stream - recording.streams.data());
  SampleMatrix& samples = referenced.streams[index].samples;
  for (const BodyPart& part : skin.body_parts) {
    for (const CellColumns& cell : part.cells) {
      for (int column : cell.force) {
        const float offset =
            rest_offset(samples.col(column), samples.col(cell.proximity), contact_mm);
        samples.col(column).array() -= offset;
      }
    }
  }
  return referenced;
}

//---- Parameters

std::string parameter_choice(const Parameters& parameters, const std::string& key,
                             const std::vector<std::string>& allowed) {
  if (!parameters.has(key)) return allowed.front();
  std::string value = parameters.text(key, allowed.front());
  std::transform(value.begin(), value.end(), value.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return value;
  std::string words;
  for (const std::string& word : allowed) words += (words.empty() ? "" : ", ") + word;
  throw Error(parameters.where(),
              key + "=" + parameters.text(key, "") + ": expected one of " + words);
}

double positive_parameter(const Parameters& parameters, const std::string& key, double fallback) {
  const double value = parameters.number(key, fallback);
  if (!(value > 0.0))
    throw Error(parameters.where(), key + "=" + parameters.text(key, "") + ": must be > 0");
  return value;
}

}  // namespace tactile
