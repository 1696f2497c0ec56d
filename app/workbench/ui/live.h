#pragma once
// Live mode: a skin streaming into the workbench (docs/LIVE.md). The receiver's thread
// hands samples over through a ring; every frame drains it into the document's live
// buffer, the recorder (if recording) and the contact detector (if recording starts by
// itself), and, following, moves the plots and the skin to the newest sample.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "services.h"
#include "workbench_state.h"

namespace tactile {

// Connects to a live source (udp://, serial://, sim://, replay://) as the open document.
// `skin` is needed for sockets and ports; sim:// and replay:// know theirs. False (and the
// reason in state.error) when the source cannot be opened.
bool connect_live(WorkbenchState& state, LiveServices& services, const std::string& url,
                  const std::string& skin);
void disconnect_live(WorkbenchState& state, LiveServices& services);
// Start of every frame: carries out the live bar's requests, takes what arrived, records,
// classifies, and copies the services' news into the state.
void poll_live(WorkbenchState& state, LiveServices& services);
// The live bar (instead of the replay transport): source, counters, buffer, follow, record;
// its buttons are requests in the state.
void draw_live_bar(WorkbenchState& state);
// Classifies the stream with a saved model (`evaluate --save-model`) from now on.
bool load_online_model(WorkbenchState& state, LiveServices& services, const std::string& path);
bool start_recording(WorkbenchState& state, LiveServices& services, const std::string& path);
bool stop_recording(WorkbenchState& state, LiveServices& services);
nlohmann::json live_json(const WorkbenchState& state);

}  // namespace tactile
