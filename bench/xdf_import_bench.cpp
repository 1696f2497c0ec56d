// What the XDF import's checks cost (issue 28): a glove session as LabRecorder writes it
// (8 float32 channels at 100 Hz in chunks of 100 samples, stamps jittered by up to 2 ms, a
// 1 s dropout every 10 minutes, a marker every 2 s, clock offsets every 5 s) of MINUTES
// minutes, then, REPEAT times each (the median is printed):
//   libxdf alone   Xdf::load_xdf of the file (its XML chunks ending in a NUL byte, so that
//                  libxdf reads within its buffers), what a reader without checks would cost
//   scan           scan_xdf: every chunk walked and checked
//   import         import_xdf: scan, the canonical copy, libxdf's load of it, clock offsets,
//                  resampling with gaps, marker pairing
// Figures are ratios to "libxdf alone", measured in one run.
//
//   xdf_import_bench [--minutes 60] [--repeat 5] [--work DIR]
#include <xdf.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "../tests/support/xdf_writer.h"
#include "tactile/formats/xdf_files.h"
#include "tactile/layout/skin_layout.h"

using tactile::testing::XdfWriter;

namespace {

void write_session(const std::string& path, int minutes, bool nul_after_xml) {
  XdfWriter writer(nul_after_xml);
  writer.stream_header(1, "TactileGlove", "Tactile", 8, 100.0, "float32");
  writer.stream_header(2, "Touches", "Markers", 1, 0.0, "string");
  const int64_t samples = int64_t{minutes} * 60 * 100;
  const char* classes[] = {"stroke", "pat", "poke", "none"};
  for (int64_t chunk = 0; chunk * 100 < samples; ++chunk) {
    std::vector<double> stamps;
    std::vector<std::vector<float>> values;
    for (int64_t k = chunk * 100; k < std::min(samples, (chunk + 1) * 100); ++k) {
      if (k % 60000 < 100 && k >= 60000) continue;  // a 1 s dropout every 10 minutes
      stamps.push_back(100.0 + 0.01 * static_cast<double>(k) +
                       0.001 * static_cast<double>((k * 7) % 5 - 2));
      std::vector<float> row(8);
      for (int c = 0; c < 8; ++c)
        row[static_cast<size_t>(c)] = std::sin(0.01f * static_cast<float>(k + 10 * c));
      values.push_back(std::move(row));
    }
    if (!stamps.empty()) writer.float_samples(1, stamps, values);
    if (chunk % 2 == 0)
      writer.string_samples(2, {100.0 + static_cast<double>(chunk) + 0.3},
                            {classes[chunk / 2 % 4]});
    if (chunk % 5 == 0)
      writer.clock_offset(1, 100.0 + static_cast<double>(chunk),
                          0.25 + 1e-6 * static_cast<double>(chunk));
    if (chunk % 5 == 0) writer.clock_offset(2, 100.0 + static_cast<double>(chunk), 0.3);
  }
  writer.save(path);
}

double median_ms(int repeat, const std::function<void()>& run) {
  std::vector<double> ms;
  for (int k = 0; k < repeat; ++k) {
    const auto begin = std::chrono::steady_clock::now();
    run();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
                     .count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int minutes = 60, repeat = 5;
  std::string work = std::filesystem::temp_directory_path() / "tactile-xdf-bench";
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--minutes")) minutes = std::atoi(argv[k + 1]);
    if (!std::strcmp(argv[k], "--repeat")) repeat = std::atoi(argv[k + 1]);
    if (!std::strcmp(argv[k], "--work")) work = argv[k + 1];
  }
  std::filesystem::create_directories(work);
  const std::string plain = work + "/session.xdf", terminated = work + "/session-nul.xdf";
  write_session(plain, minutes, false);
  write_session(terminated, minutes, true);
  const double megabytes = static_cast<double>(std::filesystem::file_size(plain)) / 1e6;
  const tactile::SkinLayout layout = tactile::make_strip_layout(8);
  int64_t rows = 0;
  size_t labels = 0;
  std::fprintf(stderr, "(libxdf prints its progress below; the import silences it)\n");
  const double alone = median_ms(repeat, [&] {
    Xdf xdf;
    xdf.load_xdf(terminated);
  });
  const double scan = median_ms(repeat, [&] { tactile::scan_xdf(plain); });
  const double import = median_ms(repeat, [&] {
    const tactile::ImportedRecording imported = tactile::import_xdf(plain, layout, {});
    rows = imported.recording.streams.front().sample_count();
    labels = imported.labels.size();
  });
  std::printf("session: %d min, %.1f MB, %lld grid rows, %zu labels; median of %d runs\n", minutes,
              megabytes, static_cast<long long>(rows), labels, repeat);
  std::printf("| step | ms | x libxdf alone | MB/s |\n|---|---|---|---|\n");
  for (const auto& [name, ms] : {std::pair<const char*, double>{"libxdf alone (load_xdf)", alone},
                                 {"scan_xdf (checks only)", scan},
                                 {"import_xdf (all)", import}})
    std::printf("| %s | %.0f | %.2f | %.0f |\n", name, ms, ms / alone, megabytes / (ms / 1000.0));
  std::filesystem::remove_all(work);
  return 0;
}
