#pragma once
// WorkbenchState: plain data of what the workbench shows: the open recording, the time
// cursor, the selection, the view arrangement, and where things were drawn on the last
// frame (so a script can name a taxel or a time instead of a pixel). Views read and
// change it; `state PATH` in a script writes it as JSON.

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "document.h"
#include "file_browser.h"
#include "files_state.h"
#include "tactile/jobs/job.h"
#include "tactile/labels/agreement.h"
#include "tactile/labels/predict.h"
#include "tactile/labels/quality.h"
#include "tactile/labels/training_job.h"
#include "tactile/live/live_receiver.h"
#include "tactile/live/live_recorder.h"
#include "tactile/live/online_classifier.h"
#include "tactile/live/playback.h"
#include "tactile/ml/evaluation.h"
#include "tactile/ml/som.h"
#include "tactile/ml/somatosensory.h"
#include "tactile/segment/fit.h"
#include "tactile/segment/scoring.h"
#include "tactile/signal/display_scale.h"
#include "tactile/video/attachments.h"
#include "tactile/video/video_player.h"
#include "tactile/video/video_sync.h"
#include "tactile/widgets/class_colours.h"
#include "tactile/widgets/signal_plot.h"
#include "tactile/widgets/skin_view.h"

namespace tactile {

struct WorkbenchState;

// One job of the window's list (jobs.h): its kind (one at a time per kind: "segmenter",
// "predict", "training", "som", "import", ...), the job, and the steps that apply its end and,
// while it runs, what it has so far.
struct WindowJob {
  std::string kind;
  std::unique_ptr<AnyJob> job;
  std::function<void(WorkbenchState&)> apply;
  std::function<void(WorkbenchState&)> while_running;  // may be empty
  bool logged = true;                                  // in the state JSON's "jobs"
};

struct ScreenRect {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  float width() const { return x1 - x0; }
  float height() const { return y1 - y0; }
  bool contains(float x, float y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

// A view whose horizontal axis is time: where the axis lay on the last frame.
struct TimeAxis {
  ScreenRect area;
  double t0 = 0.0, t1 = 1.0;
};

// Where things were drawn on the last frame (screen pixels), by name.
struct UiTargets {
  std::map<std::string, ScreenRect> items;  // "view:skin", "menu:File", "menu:File/Open..."
  // An item's whole box as laid out, also the part cut off by its view (the state's `boxes`:
  // tests hold what a view draws to fitting inside it).
  std::map<std::string, ScreenRect> boxes;
  std::map<std::string, TimeAxis> time_axes;          // view name -> axis
  std::map<int64_t, std::pair<float, float>> taxels;  // taxel id -> centre on screen
  ScreenRect skin_map;                                // the skin view's drawing area
  std::map<std::string, std::string> tips;            // a control's tooltip, by its item name
  std::map<int64_t, ScreenRect> taxel_boxes;          // taxel id -> its box as drawn
  std::vector<int64_t> touched_taxels;                // drawn enlarged as touched
  std::pair<double, double> skin_scale{0.0, 1.0};     // the colour scale's ends as drawn
  std::vector<std::pair<std::string, ScreenRect>> skin_names;  // group id or taxel name, box
};

// Sizes of the arrangement, kept per user between runs (settings file).
struct PanelSizes {
  float sidebar_width = 250.0f;
  float skin_fraction = 0.42f;     // of the width right of the sidebar
  float timeline_height = 200.0f;  // transport, label lane and label table
};

struct Selection {
  std::vector<int64_t> labels;    // label ids
  std::vector<int64_t> taxels;    // taxel ids
  std::vector<int64_t> segments;  // segment ids (classifier views)
};

// The operator's labelling: marks set by `[` and `]`, the class chosen by a digit, the
// lanes as the user arranged them (kept in the settings).
struct LabellingState {
  std::string annotator;           // --annotator, the settings, else $USER
  double reaction_seconds = 0.25;  // marks made while playing are moved back by this
  std::optional<double> mark_start, mark_end;
  std::string pending_class;            // chosen by 1-9, committed by Enter
  std::vector<std::string> lane_order;  // lane ids in the user's order (others after)
  std::set<std::string> hidden, collapsed;
  std::array<char, 256> segmenter_params{};  // typed in the Labels menu
  bool snap = true;
  bool run_cancelled_by_undo = false;       // Ctrl+Z cancelled the running segmenter job
  std::string last_segmenter = "adaptive";  // G runs it again; on opening, the skin's own
  std::string segmenter_skin;               // the skin last_segmenter was chosen for
  bool picker_open = false;                 // the type-ahead class picker (key C)
  std::array<char, 64>
      picker_text{};  // dragged times snap to segmenter and other lanes' boundaries (key S)
  // A drag in the operator's lane: over empty space it sets the marks; from an edge of
  // one of their labels it moves that edge (committed on release).
  struct LaneDrag {
    bool active = false;
    int64_t label = 0;        // 0: setting marks
    bool start_edge = false;  // which edge of `label` moves
    double press_time = 0.0;
    double time = 0.0;  // where the edge or the mark is now
  } drag;
  // A dragged edge's new bounds (label, t0, t1), committed at the start of the next
  // frame: an edit rebuilds the lanes, which the frame that drew them still uses.
  std::optional<std::tuple<int64_t, double, double>> move_request;
  // A segmenter run (G) on a worker, which also stores it (one command of the operator's, on
  // the worker's own connection to the store): what it stored.
  struct SegmentsFound {
    std::string document;  // the recording's path: the lanes are reloaded if it is still open
    std::string method, annotator;  // "threshold", "segmenter:threshold"
    size_t added = 0, rejected = 0;
  };
  // Labels > Fit segmenter to my labels, on a worker: adaptive's parameters chosen on the
  // operator's touches in the open recording (segment/fit.h), saved as the preset "fitted".
  struct SegmenterFitted {
    std::string document;
    SegmenterFit fit;
  };
  std::string active_lane() const { return "manual:" + annotator; }
};

// The model panel: the choices of the next run, what the last one was asked, and the model it
// left (Predict uses it).
struct ModelPanelState {
  std::string pipeline;  // "" = the skin's own
  std::array<char, 128> classifier{"linear-svm"};
  std::array<char, 64> protocol{"kfold:5"};
  std::array<char, 128> pipeline_params{};  // the features' parameters (key=value,...)
  LabelSource segments = LabelSource::kGroundTruth;
  TrainingRequest last_request;  // what the last run was asked (benchmarks rerun it)
  std::string model_path;        // the last single classifier trained, fitted on every row
  std::string model_classifier;  // the classifier of model_path
  // model_path's model as fitted in this session (Predict reads no file then); null when
  // only its file is known.
  std::shared_ptr<const SavedModel> model;
  // Predict on a worker, which also stores the answers (one command of the operator's).
  struct PredictionsMade {
    std::string document;  // the recording's path
    std::string model;     // the model file's name
    size_t predicted = 0;
    std::string model_path;  // the model file, written by the job when it fitted one
    std::string classifier;  // its classifier
    std::shared_ptr<const SavedModel> fitted;  // the model predicted with
  };
};

// The results: one per classifier tried (one row of the train-all table each), the feature
// table they are about, and the row whose views are shown.
struct ResultsState {
  // The running job's results as they arrive (shown at once, kept on Cancel), and how many of
  // them the rows hold.
  std::shared_ptr<TrainingSoFar> so_far;
  size_t so_far_shown = 0;
  float name_width = 0.0f;  // the table's longest classifier name so far
  std::vector<ml::PresetOutcome> rows;
  std::string from;  // what they are of ("nao, kaboli features", a file)
  int current = -1;  // the row whose views are shown
  // The feature table the results are about; shared (never changed) with the views' jobs,
  // so starting one copies nothing on the window's thread.
  std::shared_ptr<const Dataset> dataset;
  std::string dataset_layout;  // its skin
  int sort_column = 1;         // the table's: 0 name, 1 accuracy, 2 mean recall, 3 time
  bool sort_ascending = false;
};

// The confusion view: the clicked cell and its segments, and the segment landed on.
struct ConfusionState {
  int cell_true = -1, cell_predicted = -1;
  std::vector<size_t> cell_rows;  // indices into the results' rows
  int cell_selected = 0;
  bool list_active = false;  // Enter picks the selected segment
  // The segment landed on: the skin outlines its region and names both classes.
  std::optional<ml::RowPrediction> landed;
  bool landing_pending = false;  // land_on asked; carried out once its recording is open
  double replay_until = -1.0;    // the clock pauses here (the landed segment's end)
};

// The SOM view: a SOM fitted on the results' table (the job "som") or loaded, and each row's
// winner.
struct SomState {
  struct Fit {
    std::unique_ptr<ml::SomClassifier> som;
    std::vector<std::string> classes;
    std::vector<int> winners;
    std::optional<ml::SomQuality> quality;
  };
  bool held = false;  // its fit cancelled: not started again until asked
  std::unique_ptr<ml::SomClassifier> model;
  std::vector<std::string> classes;
  std::vector<int> winners;               // per dataset row
  const void* table = nullptr;            // which table the winners are for
  std::optional<ml::SomQuality> quality;  // of a map fitted here, on its table
  std::vector<double> spread;             // the U-matrix of `model`, computed once
  const void* spread_for = nullptr;
  bool u_matrix = false;
  int neuron = -1;  // clicked
};

// The scatter view: the table's rows on the first two principal components (the job
// "scatter").
struct ScatterState {
  struct Fit {
    Eigen::MatrixXd points;
    double explained = 0.0;
  };
  bool held = false;  // its PCA cancelled: not started again until asked
  Eigen::MatrixXd points;
  double explained = 0.0;
  const void* table = nullptr;
};

// The somatosensory map of the open recording (per modality), computed (the job
// "somatosensory") or from its cache.
struct SomatosensoryState {
  bool shown = false;   // the skin view shows it instead of the body map
  bool corpus = false;  // over every recording of the skin in the workspace
  std::optional<SomatosensoryMap> map;
  std::optional<SkinLayout> layout;  // the layout with its taxels moved onto the map
  std::string key;                   // recording path + modality it was made for
  // How far the map keeps the body (ml/somatosensory.h); none when too few taxels to tell.
  std::optional<MapBodyAgreement> agreement;
  struct Made {
    std::string key;
    SomatosensoryMap map;
    std::optional<MapBodyAgreement> agreement;
  };
};

// The classifier side, one part per panel or view.
struct AnalysisState {
  ModelPanelState panel;
  ResultsState results;
  ConfusionState confusion;
  SomState som;
  ScatterState scatter;
  SomatosensoryState somatosensory;
  std::string tab_request;  // a view tab to bring to front next frame
};

// A video's frame as uploaded for ImGui to draw (gl_texture.h): which frame it holds (its index,
// or a camera frame's time), and its size.
struct VideoTexture {
  uint32_t id = 0;  // 0: none yet
  double key = -1.0;
  int width = 0, height = 0;
};

// Live mode (live.h), as data: what the services (services.h) report each frame, the user's
// settings, and the requests of the live bar and its keys, carried out at the next frame's start.
struct LiveState {
  bool connected = false;  // a live source is the open document
  std::string url;
  std::string listening;         // a UDP source's address with the port it got (given as port 0)
  LiveCounters counters;         // as of this frame
  std::string failure;           // the source's, when it failed
  bool follow = true;            // plots and skin at the newest sample
  double window_seconds = 10.0;  // shown while following
  float buffer_seconds = 600.0f;
  bool resize_request = false;      // the buffer's length changed: a new buffer next frame
  double active_checked_at = -1.0;  // stream time the plot last followed the active channels
  bool channels_chosen = false;     // the moving channels are picked once data has arrived
  double scale_learnt_at = -1.0;  // stream time the colour scale was last learnt (live_rest_scale)
  std::string recording;          // the file being recorded; "" when not recording
  int64_t recorded_samples = 0;   // taken into it so far
  RecorderRoom room;              // its disk, as of the recorder's last flush
  bool recorder_automatic = false;  // started by a contact: stops after a quiet time
  std::string record_folder;        // "" = the workspace
  float pretrigger_seconds = 5.0f;
  bool auto_record = false;
  double quiet_seconds = 3.0;
  int64_t detected_until = 0;         // source index the contact detector has seen up to
  std::vector<std::string> recorded;  // files recorded in this session
  // Online classification with a saved model: its decisions, newest last.
  std::string model_path;  // "" when not classifying
  std::array<char, 512> model_input{};
  std::vector<OnlineDecision> decisions;
  std::optional<OnlineDecision> shown;  // the one written large over the skin
  // The camera beside the skin (--camera URL): its newest frame as uploaded for the video view,
  // its counters, why it stopped, and the video being recorded beside the recording.
  struct CameraShown {
    std::string url;
    std::shared_ptr<const VideoFrame> frame;  // the camera's newest, shared with it
    VideoTexture texture;                     // key: the frame's time
    int64_t received = 0;
    std::string error;
    std::string recording;  // the video file being written ("" when not recording)
  };
  std::optional<CameraShown> camera;
  // Requests (the live bar, Ctrl+R).
  bool record_request = false;                  // start recording, or stop when recording
  bool clear_request = false;                   // drop what the buffer holds
  std::optional<std::string> classify_request;  // a model file
};

// The videos attached to the open recording (video.h), each shown by a player on a worker.
struct VideoState {
  struct Shown {
    VideoAttachment attachment;
    std::string path;  // the file as opened
    std::unique_ptr<VideoPlayer> player;
    VideoTexture texture;   // the frame drawn (key: its index)
    int64_t drawn_at = -1;  // the window's frame that last drew it
  };
  std::string recording;  // the recording whose attachments these are
  std::vector<Shown> videos;
  std::string problem;  // why the attachments file could not be read
  size_t selected = 0;  // the video the keys, the marks and the proposal act on
  // An edit: the attachments before it, and the label store's newest journal row then (an undo
  // takes back the newer of a video edit and a label edit).
  struct Edit {
    std::vector<VideoAttachment> before;
    int64_t journal = 0;
    std::string what;
  };
  std::vector<Edit> undo, redo;
  bool redo_is_video = false;  // the last undo was a video's: Ctrl+Shift+Z redoes it
  // An instant where the video and the skin agree (M): recording time and video time.
  std::optional<std::pair<double, double>> mark;
  // The offset proposed from the picture's motion, for the video named `proposal_for`.
  std::optional<SyncProposal> proposal;
  std::string proposal_for;
  std::optional<VideoRegion> region;  // where the motion is looked for (none: the whole picture)
  std::string region_for;             // the video it was drawn on
  bool drawing_region = false;        // the next drag over the selected video draws the region
  // A drag over a video nudges its offset: the offset it had at the press.
  std::optional<double> drag_from;
  // A proposal's result: which video and recording it was for.
  struct Proposed {
    std::string recording, video;
    SyncProposal proposal;
  };
};

struct WorkbenchOptions {
  std::string open_path;    // a recording, or a folder (workspace) whose first recording opens
  std::string labels_path;  // label database; default labels.db beside the recording
  std::optional<double> time;
  bool play = false;
  int64_t cache_bytes = int64_t{32} << 20;  // chunk cache of the open recording
  std::string settings_path;                // "" = the user's settings file
  std::string annotator;                    // "" = the settings' or $USER
  std::string only_view;                    // draw just this view over the whole window
  std::string clip_video;                   // the one video the video view shows ("" = all)
  std::string evaluation_path;              // --evaluation RESULT.json
  std::string model_path;                   // --model MODEL.json (a SOM's map)
  std::string features_path;                // --features TABLE.csv (the scatter)
  std::string connect;                      // --connect URL (live mode)
  std::string camera;                       // --camera URL: a camera beside the live skin
  std::string skin;                         // --skin ID (for udp:// and serial://)
  std::string record_path;                  // --record FILE.h5: record from the start
  double buffer_seconds = 600.0;            // --buffer
  double pretrigger_seconds = 5.0;          // --pretrigger
};

// What the labels view last scrolled to, so it follows changes only.
struct LabelsViewState {
  int64_t followed_selection = -1;
  int64_t followed_cursor = -1;
};

struct WorkbenchState {
  WorkbenchOptions options;
  // One colour per class in every view (class_colour, views.h); unknown is neutral grey.
  ClassColours class_colours{{kUnknownClass}};
  std::unique_ptr<Document> document;
  std::string workspace;                       // absolute folder
  std::vector<std::string> workspace_files;    // absolute paths of its recordings
  std::map<std::string, std::string> damaged;  // recording path -> why it is damaged
  PlaybackClock clock;
  SignalPlotState plot;
  std::vector<char> plotted;  // per channel of the source
  int modality = 0;
  SkinViewZoom skin_zoom;
  // The skin as the skin view draws it, made again only when `key` changes: a strip laid in
  // rows that fill the panel (else the layout as it is), the distances to each taxel's
  // nearest neighbour that size its drawing, and the body regions that colour the
  // somatosensory map.
  struct SkinDrawing {
    std::string key;
    std::optional<SkinLayout> rows;  // a strip:N in rows; empty: the layout as given
    int64_t columns = 0;
    std::vector<double> neighbour_distances;
    SkinViewCategories regions;
  } skin_drawing;
  bool show_raw_values = false;  // the skin shows change from rest unless raw is asked for
  RestScale rest_scale;
  int rest_scale_modality = -1;  // modality rest_scale was computed for; -1: stale
  Selection selection;
  // The timeline's label table as last drawn: the column its header sorts by ("" = the
  // recording's order), the direction, and the label ids in the order shown.
  struct LabelTableOrder {
    std::string column;
    bool ascending = true;
    std::vector<int64_t> ids;
  };
  LabelTableOrder label_table;
  LabellingState labelling;
  AnalysisState analysis;
  LiveState live;
  std::pair<int, int> quality_lanes{0, 1};  // the lanes the quality view compares
  // The quality view's findings, computed again only when the labels or the compared
  // lanes change (not every frame).
  struct QualityCache {
    const Document* document = nullptr;
    int64_t labels_version = -1;
    std::pair<int, int> lanes{-1, -1};
    std::vector<LabelIssue> issues;
    Agreement agreement;
    TouchScore touches;  // lane B's segments against lane A's touches (segment/scoring.h)
  } quality;
  PanelSizes sizes;
  std::string error;   // the last error, shown in the status bar
  std::string notice;  // the last message (an export written, ...)
  // Why the open recording cannot be read now (its disk went away): shown while it lasts.
  std::string unavailable;
  double longest_frame_seconds = 0.0;  // the UI's slowest frame so far (building it, not drawing)
  // Every frame's building time (the first 100000): the state JSON's `since_last_state`, for
  // benchmarks of a view's cost.
  std::vector<float> frame_seconds;
  UiTargets targets;  // last frame's
  int64_t frame = 0;
  // The jobs, newest last: when each started and when it was applied, by frame.
  struct JobRecord {
    std::string name, status;  // "running", then done / failed / cancelled
    int64_t started_frame = 0, finished_frame = -1;
  };
  std::vector<JobRecord> job_log;
  // Every job whose end the window has not applied yet (jobs.h), and the jobs cancelled or
  // replaced by a newer request, kept until their worker has ended.
  std::vector<WindowJob> jobs;
  std::vector<std::unique_ptr<AnyJob>> retired_jobs;

  // Requests from views, carried out by the workbench after the frame.
  std::optional<std::string> open_request;
  std::optional<std::string> stream_request;
  std::optional<std::string> export_request;  // view name to export as PNG
  bool quit = false;
  FileBrowser file_browser;
  LabelsViewState labels_view;
  struct HelpState {
    bool keys_open = false;   // the sheet of keys (F1, Help > Keys)
    bool about_open = false;  // Help > Getting started
  } help;
  VideoState video;
  FilesState files;  // File > Open folder, Import, Export, Verify, Upgrade (files.h)
};

// Puts `message` on the status bar's error line; false, so that a step can `return fail(...)`.
inline bool fail(WorkbenchState& state, const std::string& message) {
  state.error = message;
  return false;
}

}  // namespace tactile
