// Fault benchmark of issue 27, "Several writers of one label store": two writers (two processes,
// each with its own LabelStore connection, as two workbenches are) make EDITS edits in random
// order (by seed) to one store: additions, changes, removals and changes of two labels in one
// edit, most of them on a few labels, so that conflicts happen. Each writer keeps the labels as
// it last read them, as the workbench does: read again after its own edit, after a refusal, and
// at the next frame (every 16 ms) after the change check (LabelStore::change_count) said another
// writer committed. Every edit states the revisions it saw. At the end the parent checks the
// writers' logs of accepted edits against the store:
//   lost updates       an accepted edit that is neither its label's final state nor superseded
//                      by a later accepted edit whose writer saw it
//   silent overwrites  an accepted edit whose writer had not seen the label's current revision
//                      (two accepted edits from the same revision, or one after a removal)
//   refusals naming    every refusal's message names the label ("label ID") and the other
//                      writer
// and the journal (every accepted edit journalled once, nothing else) and `verify`; and how long
// a commit of one writer takes to be seen by the other's change check (the first check after
// the commit), with the check's own cost.
//
//   label_writers_bench [--edits 1000] [--seed 1] [--labels 8] [--work DIR]
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "tactile/error.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/verify/verify.h"

namespace {

using namespace tactile;
using Clock = std::chrono::steady_clock;  // CLOCK_MONOTONIC: one clock for both processes

constexpr const char* kRecording = "rec";
const std::vector<std::string> kClasses = {"pat", "tap", "stroke", "poke"};
const std::string kWriters[2] = {"ana", "bob"};

int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
      .count();
}

Label new_label(std::mt19937_64& random, const std::string& annotator, const std::string& marker) {
  std::uniform_real_distribution<double> start(0.0, 100.0), length(0.2, 2.0);
  Label label;
  label.recording = kRecording;
  label.t0 = start(random);
  label.t1 = label.t0 + length(random);
  label.class_name = kClasses[random() % kClasses.size()];
  label.annotator = annotator;
  label.note = marker;
  return label;
}

//---- One writer (a child process)

struct WriterOptions {
  std::string path, work;
  int writer = 0;
  int edits = 0;
  uint64_t seed = 1;
};

// Writes one JSON line per accepted edit, refusal, commit and change check to WORK/NAME.log.
int run_writer(const WriterOptions& options) {
  const std::string& me = kWriters[options.writer];
  const std::string& other = kWriters[1 - options.writer];
  std::ofstream log(options.work + "/" + me + ".log");
  std::mt19937_64 random(options.seed * 2 + static_cast<uint64_t>(options.writer));
  LabelStore store(options.path, LabelStore::OpenMode::kExisting);
  std::vector<Label> view = store.list();
  int64_t changes = store.change_count();
  int64_t frame_due = now_ns();
  log << nlohmann::json{{"opened", now_ns()}}.dump() << "\n";  // what was committed before is read
  bool stale = false;
  // One change check, logged: when it started, whether it saw another writer's commit, its cost.
  auto check = [&] {
    const int64_t start = now_ns();
    const int64_t count = store.change_count();
    const int64_t end = now_ns();
    const bool changed = count != changes;
    changes = count;
    stale = stale || changed;
    log << nlohmann::json{{"check", start}, {"changed", changed}, {"ns", end - start}}.dump()
        << "\n";
  };
  for (int edit_index = 0; edit_index < options.edits; ++edit_index) {
    // Think time, checking for news like a frame loop; the view follows at frame boundaries.
    std::this_thread::sleep_for(std::chrono::microseconds(random() % 4000));
    check();
    if (stale && now_ns() >= frame_due) {
      view = store.list();
      stale = false;
      frame_due = now_ns() + 16'000'000;
    }
    const std::string marker = me + ":" + std::to_string(edit_index);
    LabelEdit edit;
    std::string kind;
    const int roll = static_cast<int>(random() % 100);
    if (view.size() < 4 || roll < 15 + (view.size() < 8 ? 15 : 0)) {
      kind = "add";
      edit.add = {new_label(random, me, marker)};
    } else if (roll < 30) {
      kind = "remove";
      edit.remove = {ref_of(view[random() % view.size()])};
    } else {
      const size_t first = random() % view.size();
      size_t second = first;
      const bool pair = roll >= 90 && view.size() > 1;
      if (pair) {
        while (second == first) second = random() % view.size();
      }
      kind = pair ? "update2" : "update";
      for (const size_t index :
           pair ? std::vector<size_t>{first, second} : std::vector<size_t>{first}) {
        Label changed = view[index];
        changed.class_name = kClasses[random() % kClasses.size()];
        changed.t1 = changed.t0 + 0.2 + static_cast<double>(random() % 1000) / 500.0;
        changed.note = marker;
        edit.update.push_back(changed);
      }
    }
    nlohmann::json entry{{"edit", edit_index}, {"kind", kind}, {"marker", marker}};
    nlohmann::json labels = nlohmann::json::array();
    for (const LabelRef& seen : edit.remove)
      labels.push_back({{"id", seen.id}, {"seen", seen.revision}});
    for (const Label& changed : edit.update)
      labels.push_back({{"id", changed.id}, {"seen", changed.revision}});
    try {
      entry["apply"] = now_ns();
      const std::vector<int64_t> ids = store.apply(edit, me);
      entry["commit"] = now_ns();
      for (const int64_t id : ids) labels.push_back({{"id", id}, {"seen", 0}});
      entry["accepted"] = true;
      view = store.list();  // the workbench reloads after its own edit
      stale = false;
    } catch (const EditConflict& conflict) {
      entry["accepted"] = false;
      entry["message"] = conflict.message();
      entry["conflict_label"] = conflict.label_id();
      entry["conflict_annotator"] = conflict.annotator();
      entry["other"] = other;
      view = store.list();  // refused: read again
      stale = false;
    } catch (const Error& error) {
      entry["accepted"] = false;
      entry["message"] = error.what();
      entry["not_a_conflict"] = true;
      entry["other"] = other;
      view = store.list();
      stale = false;
    }
    entry["labels"] = labels;
    log << entry.dump() << "\n";
  }
  // Keep checking until the other writer is done too, so that its last commits are seen.
  std::ofstream(options.work + "/" + me + ".done") << "done\n";
  const int64_t until = now_ns() + 60'000'000'000;
  while (!std::filesystem::exists(options.work + "/" + other + ".done") && now_ns() < until) {
    std::this_thread::sleep_for(std::chrono::microseconds(1000));
    check();
  }
  for (int extra = 0; extra < 20; ++extra) {
    std::this_thread::sleep_for(std::chrono::microseconds(1000));
    check();
  }
  log.flush();
  return log ? 0 : 1;
}

//---- The parent: the logs checked against the store

std::vector<nlohmann::json> read_log(const std::string& path) {
  std::vector<nlohmann::json> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

struct Accepted {
  std::string writer, kind, marker;
  int64_t seen = 0;  // the revision the writer saw (0: its addition)
};

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<size_t>(fraction * static_cast<double>(values.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
  int edits = 1000, initial = 8;
  uint64_t seed = 1;
  std::string work = "/tmp/tactile-label-writers-bench";
  for (int index = 1; index + 1 < argc; index += 2) {
    const std::string option = argv[index], value = argv[index + 1];
    if (option == "--edits")
      edits = std::stoi(value);
    else if (option == "--seed")
      seed = std::stoull(value);
    else if (option == "--labels")
      initial = std::stoi(value);
    else if (option == "--work")
      work = value;
    else {
      std::cerr << "usage: label_writers_bench [--edits N] [--seed S] [--labels N] [--work DIR]\n";
      return 2;
    }
  }
  std::filesystem::remove_all(work);
  std::filesystem::create_directories(work);
  const std::string path = work + "/labels.db";
  {
    LabelStore store(path);
    store.set_classes("bench", kClasses);
    std::mt19937_64 random(seed);
    LabelEdit setup;
    for (int index = 0; index < initial; ++index)
      setup.add.push_back(new_label(random, "setup", "setup:" + std::to_string(index)));
    store.apply(setup, "setup");
  }
  pid_t children[2] = {0, 0};
  for (int writer = 0; writer < 2; ++writer) {
    children[writer] = fork();
    if (children[writer] == 0) {
      int code = 1;
      try {
        code = run_writer({path, work, writer, edits / 2 + (writer == 0 ? edits % 2 : 0), seed});
      } catch (const std::exception& error) {
        std::cerr << kWriters[writer] << ": " << error.what() << "\n";
      }
      _exit(code);
    }
  }
  for (const pid_t child : children) {
    int status = 0;
    waitpid(child, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::cerr << "a writer failed\n";
      return 1;
    }
  }

  // Accepted edits per label, refusals, commits and checks per writer.
  std::map<int64_t, std::vector<Accepted>> by_label;
  int total = 0, accepted = 0, refused = 0, refusals_naming = 0, not_conflicts = 0;
  std::map<std::string, std::map<std::string, int>> journal_expected;  // writer -> action -> rows
  std::map<std::string, std::vector<std::pair<int64_t, int64_t>>> commits;  // apply, returned
  std::map<std::string, std::vector<int64_t>> checks, check_ends;
  std::map<std::string, std::vector<bool>> check_changed;
  std::vector<double> check_ns;
  std::map<std::string, int64_t> opened;
  for (const std::string& writer : kWriters) {
    for (const nlohmann::json& line : read_log(work + "/" + writer + ".log")) {
      if (line.contains("opened")) {
        opened[writer] = line["opened"].get<int64_t>();
        continue;
      }
      if (line.contains("check")) {
        checks[writer].push_back(line["check"].get<int64_t>());
        check_ends[writer].push_back(line["check"].get<int64_t>() + line["ns"].get<int64_t>());
        check_changed[writer].push_back(line["changed"].get<bool>());
        check_ns.push_back(line["ns"].get<double>());
        continue;
      }
      ++total;
      const std::string kind = line["kind"];
      if (line["accepted"].get<bool>()) {
        ++accepted;
        commits[writer].push_back({line["apply"].get<int64_t>(), line["commit"].get<int64_t>()});
        for (const nlohmann::json& label : line["labels"]) {
          const int64_t id = label["id"].get<int64_t>();
          const std::string action = kind == "add"      ? "insert"
                                     : kind == "remove" ? "delete"
                                                        : "update";
          ++journal_expected[writer][action];
          by_label[id].push_back({writer, kind == "update2" ? "update" : kind,
                                  line["marker"].get<std::string>(), label["seen"].get<int64_t>()});
        }
      } else {
        ++refused;
        if (line.contains("not_a_conflict")) ++not_conflicts;
        const std::string message = line["message"];
        bool names_label = false;
        for (const nlohmann::json& label : line["labels"])
          names_label = names_label ||
                        message.find("label " + std::to_string(label["id"].get<int64_t>()) + " ") !=
                            std::string::npos;
        const bool names_other =
            message.find(" by " + line["other"].get<std::string>() + " ") != std::string::npos;
        if (names_label && names_other) ++refusals_naming;
      }
    }
  }

  // Each label's accepted edits form one chain of revisions: the addition (revision 1), then
  // edits each seeing the revision the one before made; a removal ends it.
  LabelStore store(path, LabelStore::OpenMode::kExisting);
  std::map<int64_t, Label> final_labels;
  for (const Label& label : store.list()) final_labels[label.id] = label;
  int lost = 0, overwrites = 0;
  for (auto& [id, edits_of_label] : by_label) {
    std::stable_sort(edits_of_label.begin(), edits_of_label.end(),
                     [](const Accepted& a, const Accepted& b) { return a.seen < b.seen; });
    // A label of the setup starts at revision 1 with no accepted addition in the logs.
    int64_t revision = edits_of_label.front().kind == "add" ? 0 : 1;
    bool removed = false;
    for (size_t k = 0; k < edits_of_label.size(); ++k) {
      const Accepted& edit = edits_of_label[k];
      if (edit.kind == "add") {
        revision = 1;
        continue;
      }
      // Accepted although the writer had not seen the current revision, or after a removal.
      if (removed || edit.seen != revision) ++overwrites;
      if (edit.kind == "remove")
        removed = true;
      else
        revision = edit.seen + 1;
    }
    // An accepted edit whose result nobody saw and that is not the final state was lost.
    for (size_t k = 0; k < edits_of_label.size(); ++k) {
      const Accepted& edit = edits_of_label[k];
      if (edit.kind == "remove") continue;
      const int64_t made = edit.kind == "add" ? 1 : edit.seen + 1;
      const bool superseded = std::any_of(
          edits_of_label.begin(), edits_of_label.end(),
          [&](const Accepted& later) { return later.kind != "add" && later.seen == made; });
      const auto final_label = final_labels.find(id);
      const bool is_final = final_label != final_labels.end() &&
                            final_label->second.note == edit.marker &&
                            final_label->second.revision == made;
      if (!superseded && !is_final) ++lost;
    }
    const bool gone = final_labels.count(id) == 0;
    if (removed != gone) ++lost;  // a removal undone unseen, or a label gone without one
  }

  // The journal holds every accepted edit once and nothing else.
  std::map<std::string, std::map<std::string, int>> journal_found;
  for (const JournalEntry& entry : store.journal(-1))
    if (entry.annotator != "setup") ++journal_found[entry.annotator][entry.action];
  const bool journal_matches = journal_found == journal_expected;
  const bool verified = verify_label_store(path).empty() && store.check().empty();

  // Visibility: from a commit of one writer (its apply() returned) to the other's first change
  // check after it, which must say "changed". A commit is visible a little before apply()
  // returns (the WAL's fsync comes last): a check that ended during the apply and said
  // "changed" saw it, with no delay (a check may be preempted between its start and its read).
  // Commits before the other writer opened the store are in what it read first.
  std::vector<double> latency_ms;
  int missed = 0;
  for (int writer = 0; writer < 2; ++writer) {
    const std::string& seer = kWriters[1 - writer];
    const std::vector<int64_t>& seen_at = checks[seer];
    const std::vector<bool>& changed = check_changed[seer];
    for (const auto& [apply, commit] : commits[kWriters[writer]]) {
      if (commit < opened[seer]) continue;
      const size_t next = static_cast<size_t>(
          std::upper_bound(seen_at.begin(), seen_at.end(), commit) - seen_at.begin());
      bool during = false;
      for (size_t k = next; k-- > 0 && check_ends[seer][k] >= apply;) during = during || changed[k];
      if (next < seen_at.size() && changed[next])
        latency_ms.push_back(static_cast<double>(seen_at[next] - commit) / 1e6);
      else if (during)
        latency_ms.push_back(0.0);
      else
        ++missed;
    }
  }

  std::printf(
      "| edits | accepted | refused | lost updates | silent overwrites | refusals naming "
      "label + annotator | visibility latency max (p99, median) | change check cost (median) |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  std::printf("| %d | %d | %d | %d | %d | %d of %d | %.1f ms (%.1f ms, %.2f ms) | %.1f us |\n",
              total, accepted, refused, lost, overwrites, refusals_naming, refused,
              percentile(latency_ms, 1.0), percentile(latency_ms, 0.99),
              percentile(latency_ms, 0.5), percentile(check_ns, 0.5) / 1e3);
  std::printf(
      "\nseed %llu, 2 writers (processes), %d labels to start; refusals that were no "
      "conflict: %d; commits the other's change check missed: %d; journal matches the "
      "accepted edits: %s; verify: %s\n",
      static_cast<unsigned long long>(seed), initial, not_conflicts, missed,
      journal_matches ? "yes" : "NO", verified ? "passes" : "FAILS");
  const bool sound = lost == 0 && overwrites == 0 && refusals_naming == refused && missed == 0 &&
                     journal_matches && verified && not_conflicts == 0;
  return sound ? 0 : 1;
}
