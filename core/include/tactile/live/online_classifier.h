#pragma once
// Classifying a live stream as it arrives (docs/LIVE.md, "Online classification"), so the
// stream is classified continuously and not only in touches cut out afterwards. Every hop,
// the last `lookback_seconds` of the stream go to a worker thread, which runs the skin's own
// segmenter over them (the one its paper's experiment uses) and then:
//  - a segment that ended at least `release_seconds` ago and was not decided yet: the whole
//    touch is classified (a final decision; the latency benchmark times these);
//  - a segment still open: its last `window_seconds` are classified (provisional);
//  - no segment over the hop: "no touch", the class that comes from windows with no contact.
// The saved model's own feature pipeline and classifier do the work; the frame only copies
// samples.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "tactile/labels/predict.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/live/live_source.h"
#include "tactile/parameters.h"
#include "tactile/skins/skin.h"

namespace tactile {

inline constexpr const char* kNoTouchClass = "no touch";

// OnlineOptions, and each skin's defaults (default_online_options), are in its record
// (skins/skin.h): the segmenter of its paper's experiment (nao proximity, tsa frame-edge, fur
// threshold, flux excitation; robovie's scenario needs a protocol's time stamps, so
// adaptive), a window as long as its touches run, a hop of 0.1 s (tsa: two frames at 8 Hz).

struct OnlineDecision {
  double t0 = 0.0, t1 = 0.0;  // device time the decision is about
  std::string class_name;     // kNoTouchClass, a class of the model, or "unknown"
  double score = 0.0;         // the model's confidence; for "no touch" how far inside the band
  bool final = false;         // made at the end of a touch
  double seconds = 0.0;       // wall time from asking to answering
};

// The annotator of online decisions as labels (transient labels of the prediction lane).
inline constexpr const char* kOnlineAnnotator = "online";

// One decision into the lane of online labels (source model, annotator kOnlineAnnotator, note
// "provisional" or "final"): a provisional answer that goes on in the same class grows the last
// label; a new one starts where the one before ends (the windows overlap); a touch's final
// answer replaces the provisional labels over it. Labels that end before `oldest` (what the
// live buffer no longer holds) go.
void add_online_decision(std::vector<Label>& lane, const OnlineDecision& decision,
                         const std::string& recording, double oldest);

class OnlineClassifier {
 public:
  // Throws tactile::Error when the model has no pipeline or is of another skin.
  OnlineClassifier(SavedModel model, SkinLayout layout, const SourceInfo& stream,
                   OnlineOptions options);
  ~OnlineClassifier();
  OnlineClassifier(const OnlineClassifier&) = delete;
  OnlineClassifier& operator=(const OnlineClassifier&) = delete;

  // UI thread: looks at the samples that arrived since the last call and asks for
  // decisions (no-touch ones are made here; the others are queued for the worker).
  void update(const LiveSampleSource& source);
  // Decisions made since the last call, in the order they were made.
  std::vector<OnlineDecision> take();
  bool in_touch() const;
  // Waits until the worker has decided every hop asked for (tests and benchmarks).
  void wait_idle();  // the last segmentation found a touch still going on
  const OnlineOptions& options() const { return options_; }
  // The last error of the worker (a pipeline that refused a window), "" when none.
  std::string error() const;

 private:
  struct Job {
    Recording window;  // the last lookback seconds
    double now = 0.0;  // device time of its newest sample
  };
  void run();
  void decide(const Job& job);
  void classify(const Job& job, double t0, double t1, const std::string& region, bool final);

  SavedModel model_;
  SkinLayout layout_;
  OnlineOptions options_;
  Parameters segmenter_params_;
  double rate_;
  int64_t next_hop_ = -1;  // source index of the next hop
  // Worker side.
  double decided_until_ = -1e300;  // end of the last touch given a final decision
  double last_now_ = -1e300;
  bool in_touch_ = false;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<Job> pending_;  // only the newest hop waits
  bool working_ = false;
  std::condition_variable idle_;
  std::vector<OnlineDecision> done_;
  std::string error_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace tactile
