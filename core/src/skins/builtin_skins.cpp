// The papers' five skins (../shared/seeds/README.md). A new skin is one more record like
// these, registered by the program or the test that brings it (register_skin).
#include <vector>

#include "tactile/skins/skin.h"

namespace tactile {

std::vector<SkinRecord> builtin_skins() {
  std::vector<SkinRecord> skins(5);

  // Paper 000: NAO humanoid, 32 cells of accelerometer, force, proximity and temperature.
  SkinRecord& nao = skins[0];
  nao.id = "nao";
  nao.name = "NAO humanoid, 32 multi-modal cells (paper 000)";
  nao.simulate = simulate_nao_trial;
  nao.demo_subjects = 2;
  nao.demo_repetitions = 1;
  nao.pipeline = "kaboli";
  nao.segmenter = "proximity";
  // Accelerometer +-2 g on a signed 10-bit ADC, force 0-3 N on 12 bits, proximity 1-200 mm
  // on 16 bits, temperature in 0.01 degC: per modality, in live/packets.h's cell record.
  nao.packet = PacketFormat{"", 1, 250.0, 1, 32 * 8, WireWord::kNaoCells, {}};
  // Kaboli's window already reaches 0.1 s past the last proximity sample (spec §1.1): a
  // segment ending before the newest sample has been quiet that long.
  nao.online.segmenter = "proximity";
  nao.online.hop_seconds = 0.05;
  nao.online.release_seconds = 0.0;
  nao.online.lookback_seconds = 4.0;

  // Paper 001: capacitive arrays inside an ABS shell, 21 modules of 32 channels.
  SkinRecord& tsa = skins[1];
  tsa.id = "tsa";
  tsa.name = "capacitive arrays in an ABS shell, 21 modules (paper 001)";
  tsa.simulate = simulate_tsa_trial;
  tsa.demo_subjects = 2;
  tsa.demo_repetitions = 2;
  tsa.pipeline = "tsa_event";
  tsa.segmenter = "frame-edge";
  // 21 FEE modules x 32 channels of 12 bits at 8 Hz.
  tsa.packet = PacketFormat{"", 2, 8.0, 1, 672, WireWord::kPacked12, {0.0, 1.0, 0, 4095}};
  tsa.online.segmenter = "frame-edge";
  tsa.online.window_seconds = 3.0;
  tsa.online.hop_seconds = 0.25;  // two frames at 8 Hz
  tsa.online.release_seconds = 0.25;
  tsa.online.lookback_seconds = 12.0;  // the trigger's baseline needs its idle span

  // Paper 002: smart fur, a 160-cell pressure matrix under plush.
  SkinRecord& fur = skins[2];
  fur.id = "fur";
  fur.name = "smart fur, 160-cell pressure matrix (paper 002)";
  fur.simulate = simulate_fur_trial;
  fur.demo_subjects = 2;
  fur.demo_repetitions = 2;
  fur.pipeline = "fur";
  fur.segmenter = "threshold";
  // ATMEGA32 10-bit ADC, 160 cells sent over USB at 15 Hz.
  fur.packet = PacketFormat{"", 3, 15.0, 1, 160, WireWord::kUint16, {0.0, 1.0, 0, 1023}};
  fur.online.segmenter = "threshold";
  fur.online.window_seconds = 3.0;

  // Paper 003: 274 piezo films in the skin of Robovie-IIF.
  SkinRecord& robovie = skins[3];
  robovie.id = "robovie";
  robovie.name = "Robovie-IIF, 274 piezo films (paper 003)";
  robovie.simulate = simulate_robovie_trial;
  robovie.demo_subjects = 1;
  robovie.pipeline = "robovie_xcorr";
  // Its experiment's scenario segmenter needs the protocol's time stamps, which a recording
  // of anyone else lacks.
  robovie.segmenter = "adaptive";
  // Its labels are the scenario's interactions, several contacts each: contacts less than
  // 1.5 s apart stay one touch. Piezo films answer a slap and a stroke orders of magnitude
  // apart, so a share of the strongest touch is no floor for them: the noise band alone
  // (share=0; bench/SEGMENT.md: 0.729 / 0.827 against 0.372 / 0.771 with adaptive's 0.2).
  robovie.segmenter_params = "join_seconds=1.5,share=0";
  // 274 films on a 16-bit A/D at 100 Hz.
  robovie.packet = PacketFormat{"", 4, 100.0, 1, 274, WireWord::kInt16, {0.0, 1.0, -32768, 32767}};

  // Paper 004: soft silicone flux sensor, 2 x 4 serpentines.
  SkinRecord& flux = skins[4];
  flux.id = "flux";
  flux.name = "silicone flux sensor, 2 x 4 serpentines (paper 004)";
  flux.simulate = simulate_flux_trial;
  flux.demo_subjects = 1;
  flux.demo_repetitions = 2;
  flux.pipeline = "flux";
  flux.segmenter = "excitation";
  // Arduino UNO, 8 channels of 10 bits at 1 kHz; 10 samples a datagram.
  flux.packet = PacketFormat{"", 5, 1000.0, 10, 8, WireWord::kUint16, {0.0, 1.0, 0, 1023}};
  // A window as long as its touches run: the 5 s analysis window of spec §5.5.
  flux.online.segmenter = "excitation";
  flux.online.window_seconds = 5.0;
  flux.online.lookback_seconds = 10.0;

  return skins;
}

}  // namespace tactile
