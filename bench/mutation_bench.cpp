// Mutation benchmark of issue "Files that cannot lie": damaged copies of a recording
// and of a label store (bit flips, overwritten bytes, zeroed runs, truncation), each
// read in a child process as `tactile info` + `tactile export` (recording) and
// `tactile labels export` + the journal (label store) read it, with a time limit.
// Every copy lands in one column:
//   refused    the reader said it is damaged (an error, or a damaged row named)
//   same       accepted, the content read equals the original's
//   different  accepted, different content: a silent corruption
//   crash      the child died of a signal (or a sanitizer report)
//   hang       no answer within the time limit
// and `tactile verify` is run on it too: every copy refused, crashed or different
// must be reported by verify.
//
//   mutation_bench --recording FILE.h5 --labels FILE.db [--copies N] [--seed S]
//                  [--timeout SECONDS] [--work DIR] [--sweep] [--edit-labels]
// --edit-labels: first gives the store an operator's history (edits, a removal,
// undo and redo).
// --sweep: instead of random copies, one copy per byte with its lowest bit flipped,
// and the byte ranges whose change reads back the same listed (bytes that carry
// nothing: free space, padding).
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/verify/verify.h"

namespace {

using namespace tactile;

enum Outcome : char { kRefused = 'R', kSame = 'S', kDifferent = 'D', kCrash = 'C', kHang = 'H' };

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// What `tactile info --json` and `tactile export` show of a recording (everything),
// and the min/max overview the workbench draws when zoomed out.
std::string recording_content(const std::string& path) {
  const Recording recording = read_recording(path);
  const RecordingFile file(path);
  std::ostringstream out;
  out << recording.id << '\n' << recording.layout_id << '\n';
  for (const auto& [key, value] : recording.metadata) out << key << '=' << value << '\n';
  for (const Stream& stream : recording.streams) {
    out << stream.name << ' ' << stream.rate_hz << ' ' << stream.start_time << '\n';
    for (const std::string& channel : stream.channels) out << channel << ',';
    for (const std::string& unit : stream.units) out << unit << ',';
    out.write(reinterpret_cast<const char*>(stream.samples.data()),
              static_cast<std::streamsize>(sizeof(float) * stream.samples.size()));
    out.write(reinterpret_cast<const char*>(stream.timestamps.data()),
              static_cast<std::streamsize>(sizeof(double) * stream.timestamps.size()));
    const auto [minima, maxima] = file.read_overview(stream.name);
    for (const SampleMatrix* overview : {&minima, &maxima})
      out.write(reinterpret_cast<const char*>(overview->data()),
                static_cast<std::streamsize>(sizeof(float) * overview->size()));
  }
  return out.str();
}

// What `tactile labels export --json` shows, and the journal an undo walks.
std::string store_content(const std::string& path) {
  const LabelStore store(path, LabelStore::OpenMode::kExisting);
  std::string content = labels_json(store.list());
  for (const JournalEntry& entry : store.journal(-1))
    content += std::to_string(entry.sequence) + entry.time + entry.annotator + entry.action +
               std::to_string(entry.label_id) + entry.before_json + entry.after_json +
               (entry.undone ? "u" : "") + std::to_string(entry.batch) + "\n";
  if (!store.problems().empty())
    throw Error(path, store.problems().front().where(path) + ": " + store.problems().front().what);
  return content;
}

// Gives a simulated store the history an operator leaves: edits, removals, an undo
// and a redo, so journal rows carry every field (undone, undone_by, before and after).
void edit_store(const std::string& path) {
  LabelStore store(path, LabelStore::OpenMode::kExisting);
  store.use_fixed_time("2026-11-25T08:00:00.000Z");
  const std::vector<Label> labels = store.list();
  for (size_t index = 0; index < labels.size(); index += 3) {
    Label edited = labels[index];
    edited.t1 += 0.125;
    edited.annotator = "operator";
    edited.note = "checked";
    store.update(edited);
  }
  if (labels.size() > 2) store.remove(ref_of(labels[1]), "operator");
  store.undo();
  store.redo();
  store.undo();
}

struct Mutation {
  std::string kind;
  std::string bytes;
};

// The sweep: every byte in turn, its lowest bit flipped.
Mutation flip_at(const std::string& original, size_t offset) {
  Mutation mutation{"bit flip", original};
  mutation.bytes[offset] ^= 1;
  return mutation;
}

Mutation mutate(const std::string& original, std::mt19937_64& random) {
  Mutation mutation{"", original};
  std::string& bytes = mutation.bytes;
  auto offset = [&](size_t limit) {
    return std::uniform_int_distribution<size_t>(0, limit - 1)(random);
  };
  switch (std::uniform_int_distribution<int>(0, 3)(random)) {
    case 0: {
      mutation.kind = "bit flip";
      bytes[offset(bytes.size())] ^= static_cast<char>(1u << offset(8));
      break;
    }
    case 1: {
      mutation.kind = "overwritten bytes";
      const size_t count = 1 + offset(16);
      const size_t at = offset(bytes.size());
      for (size_t index = at; index < std::min(bytes.size(), at + count); ++index)
        bytes[index] = static_cast<char>(offset(256));
      break;
    }
    case 2: {
      mutation.kind = "zeroed run";
      const size_t count = 1 + offset(4096);
      const size_t at = offset(bytes.size());
      std::fill(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                bytes.begin() + static_cast<std::ptrdiff_t>(std::min(bytes.size(), at + count)),
                '\0');
      break;
    }
    default: {
      mutation.kind = "truncation";
      bytes.resize(offset(bytes.size()));
      break;
    }
  }
  return mutation;
}

struct ChildResult {
  Outcome read = kRefused;
  bool verify_flagged = false;
  std::string message;
};

// Runs `work` in a child process; its answer comes back through a pipe.
ChildResult run_child(const std::function<ChildResult()>& work, double timeout_seconds) {
  int channel[2];
  if (pipe(channel) != 0) throw std::runtime_error("pipe");
  const pid_t child = fork();
  if (child == 0) {
    close(channel[0]);
    ChildResult result = work();
    std::string answer = {static_cast<char>(result.read), result.verify_flagged ? 'V' : '-'};
    answer += result.message.substr(0, 300);
    (void)!write(channel[1], answer.data(), answer.size());
    close(channel[1]);
    _exit(0);
  }
  close(channel[1]);
  ChildResult result;
  std::string answer;
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::milliseconds(static_cast<int64_t>(timeout_seconds * 1000));
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd descriptor{channel[0], POLLIN, 0};
    if (poll(&descriptor, 1, static_cast<int>(left.count())) <= 0) continue;
    char buffer[512];
    const ssize_t got = read(channel[0], buffer, sizeof(buffer));
    if (got <= 0) break;
    answer.append(buffer, static_cast<size_t>(got));
  }
  close(channel[0]);
  if (timed_out) kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  if (timed_out) {
    result.read = kHang;
    result.verify_flagged = true;  // unknown: counted in the hang column
    return result;
  }
  if (answer.size() < 2 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    result.read = kCrash;
    result.message = WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                         : "exit " + std::to_string(WEXITSTATUS(status));
    result.verify_flagged = true;
    return result;
  }
  result.read = static_cast<Outcome>(answer[0]);
  result.verify_flagged = answer[1] == 'V';
  result.message = answer.substr(2);
  return result;
}

struct Tally {
  std::map<char, int> outcomes;
  int copies = 0;
  int verify_missed = 0;  // refused or different, yet verify reported nothing
  int unchanged = 0;      // copies whose mutation left every byte as it was (zeros zeroed)
  std::vector<std::string> examples;  // silent, crash, hang and verify misses
};

void print_row(const std::string& name, const Tally& tally) {
  auto count = [&](Outcome outcome) {
    const auto found = tally.outcomes.find(outcome);
    return found == tally.outcomes.end() ? 0 : found->second;
  };
  std::cout << "| " << name << ", " << tally.copies << " | " << count(kRefused) << " | "
            << count(kSame) << " | " << count(kDifferent) << " | " << count(kCrash) << " | "
            << count(kHang) << " | " << tally.copies - tally.verify_missed - count(kSame) << " of "
            << tally.copies - count(kSame) << " |\n";
}

Tally run(const std::string& original_path, bool recording, int copies, uint64_t seed,
          double timeout, const std::filesystem::path& work, bool sweep) {
  const std::string original = read_bytes(original_path);
  const std::string expected =
      recording ? recording_content(original_path) : store_content(original_path);
  std::mt19937_64 random(seed);
  Tally tally;
  const std::string extension = recording ? ".h5" : ".db";
  if (sweep) copies = static_cast<int>(original.size());
  std::vector<std::pair<size_t, size_t>> same_ranges;  // sweep: offsets that carry nothing
  for (int copy = 0; copy < copies; ++copy) {
    const Mutation mutation =
        sweep ? flip_at(original, static_cast<size_t>(copy)) : mutate(original, random);
    const std::string path = (work / ("copy" + extension)).string();
    for (const char* suffix : {"", "-wal", "-shm", "-journal"})
      std::filesystem::remove(path + suffix);
    write_bytes(path, mutation.bytes);
    const ChildResult result = run_child(
        [&]() {
          ChildResult answer;
          try {
            const std::string content = recording ? recording_content(path) : store_content(path);
            answer.read = content == expected ? kSame : kDifferent;
          } catch (const std::exception& error) {
            answer.read = kRefused;
            answer.message = error.what();
          }
          // verify reads its own copy: the reader above may have changed the store.
          write_bytes(path, mutation.bytes);
          for (const char* suffix : {"-wal", "-shm"}) std::filesystem::remove(path + suffix);
          try {
            const auto problems = recording ? verify_recording(path) : verify_label_store(path);
            answer.verify_flagged = !problems.empty();
          } catch (const std::exception&) {
            answer.verify_flagged = true;
          }
          return answer;
        },
        timeout);
    ++tally.copies;
    ++tally.outcomes[result.read];
    tally.unchanged += mutation.bytes == original;
    if (sweep && result.read == kSame) {
      const auto offset = static_cast<size_t>(copy);
      if (!same_ranges.empty() && same_ranges.back().second == offset)
        same_ranges.back().second = offset + 1;
      else
        same_ranges.emplace_back(offset, offset + 1);
    }
    const bool missed = result.read != kSame && !result.verify_flagged;
    tally.verify_missed += missed;
    if ((result.read == kDifferent || result.read == kCrash || result.read == kHang || missed) &&
        tally.examples.size() < 20) {
      const std::string name = (work / ("example-" + std::to_string(copy) + extension)).string();
      write_bytes(name, mutation.bytes);
      std::string example(1, static_cast<char>(result.read));
      if (missed) example += " (verify missed)";
      example += " " + mutation.kind + ": " + name + " " + result.message;
      tally.examples.push_back(std::move(example));
    }
  }
  if (sweep)
    for (const auto& [first, end] : same_ranges)
      std::cerr << "carries nothing: [" << first << ", " << end << ") " << end - first
                << " bytes\n";
  return tally;
}

}  // namespace

int main(int argc, char** argv) {
  std::string recording, labels, work = "/tmp/tactile-mutation-bench";
  int copies = 10000;
  uint64_t seed = 1;
  double timeout = 30.0;
  bool sweep = false;
  bool edit_labels = false;
  for (int index = 1; index < argc; index += 2) {
    const std::string option = argv[index];
    if (option == "--sweep" || option == "--edit-labels") {
      (option == "--sweep" ? sweep : edit_labels) = true;
      --index;
      continue;
    }
    if (index + 1 >= argc) {
      std::cerr << "mutation_bench: " << option << " needs a value\n";
      return 2;
    }
    const std::string value = argv[index + 1];
    if (option == "--recording")
      recording = value;
    else if (option == "--labels")
      labels = value;
    else if (option == "--copies")
      copies = std::stoi(value);
    else if (option == "--seed")
      seed = std::stoull(value);
    else if (option == "--timeout")
      timeout = std::stod(value);
    else if (option == "--work")
      work = value;
    else {
      std::cerr << "mutation_bench: unknown option " << option << "\n";
      return 2;
    }
  }
  if (recording.empty() && labels.empty()) {
    std::cerr << "usage: mutation_bench --recording FILE.h5 --labels FILE.db [--copies N] "
                 "[--seed S] [--timeout SECONDS] [--work DIR]\n";
    return 2;
  }
  std::filesystem::create_directories(work);
  if (edit_labels && !labels.empty()) edit_store(labels);
  std::cout << "| input (mutated copies) | refused | accepted, same | accepted, different (silent) "
               "| crash | hang > "
            << timeout << " s | verify reports the damaged |\n|---|---|---|---|---|---|---|\n";
  std::vector<std::string> examples;
  bool clean = true;
  for (const auto& [path, is_recording] : {std::pair{recording, true}, std::pair{labels, false}}) {
    if (path.empty()) continue;
    const auto start = std::chrono::steady_clock::now();
    const Tally tally = run(path, is_recording, copies, seed, timeout, work, sweep);
    print_row(std::filesystem::path(path).filename().string(), tally);
    std::cerr << path << ": " << tally.unchanged
              << " copies were left byte for byte unchanged by their mutation\n";
    std::cerr << path << ": " << tally.copies << " copies in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s\n";
    examples.insert(examples.end(), tally.examples.begin(), tally.examples.end());
    for (char bad : {kDifferent, kCrash, kHang})
      if (tally.outcomes.count(bad) > 0) clean = false;
    if (tally.verify_missed > 0) clean = false;
  }
  for (const std::string& example : examples) std::cerr << example << "\n";
  return clean ? 0 : 1;
}
