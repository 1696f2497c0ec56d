#pragma once
// EDF+ and BDF+ files written by EDFlib itself (the writer labs' own tools use), for the EDF
// reader's tests, the command-line test and the fuzz seeds. Every value is a function of the
// signal and the sample index, written as a digital value, so the physical value the file holds
// is known exactly and a test checks what it reads one value at a time.

#include <edflib.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace tactile::testing {

struct EdfTestSignal {
  std::string label;
  int samples_per_record = 0;
  double physical_min = 0.0, physical_max = 0.0;
  int digital_min = 0, digital_max = 0;
  std::string unit;
};

struct EdfTestAnnotation {
  double onset = 0.0;      // seconds
  double duration = -1.0;  // seconds; < 0: none
  std::string text;
};

struct EdfTestFile {
  bool bdf = false;
  std::vector<EdfTestSignal> signals;
  int records = 1;
  double record_seconds = 1.0;
  std::vector<EdfTestAnnotation> annotations;
  bool header_fields = true;  // patient, technician, equipment, start date and time
};

// Signal `signal`'s digital value at sample `index`: 80% of its digital range, a sine per signal.
inline int edf_test_digital(const EdfTestSignal& signal, int number, long long index) {
  const double middle = 0.5 * (signal.digital_max + static_cast<double>(signal.digital_min));
  const double half_range = 0.5 * (signal.digital_max - static_cast<double>(signal.digital_min));
  return static_cast<int>(std::lround(
      middle + 0.8 * half_range * std::sin(0.05 * static_cast<double>(index) + number)));
}

// The physical value the file holds there: written digitally, so exactly this (EDF's scaling).
inline double edf_test_value(const EdfTestSignal& signal, int number, long long index) {
  const double step = (signal.physical_max - signal.physical_min) /
                      static_cast<double>(signal.digital_max - signal.digital_min);
  return signal.physical_min +
         step * (edf_test_digital(signal, number, index) - signal.digital_min);
}

inline void edf_test_check(int result, const char* what) {
  if (result != 0) throw std::runtime_error(std::string("EDFlib refused ") + what);
}

inline void write_edf_test_file(const std::string& path, const EdfTestFile& spec) {
  const int handle = edfopen_file_writeonly(
      path.c_str(), spec.bdf ? EDFLIB_FILETYPE_BDFPLUS : EDFLIB_FILETYPE_EDFPLUS,
      static_cast<int>(spec.signals.size()));
  if (handle < 0) throw std::runtime_error("EDFlib cannot write " + path);
  edf_test_check(edf_set_datarecord_duration(
                     handle, static_cast<int>(std::lround(spec.record_seconds * 100000))),
                 "the record duration");
  for (size_t k = 0; k < spec.signals.size(); ++k) {
    const EdfTestSignal& signal = spec.signals[k];
    const int index = static_cast<int>(k);
    edf_test_check(edf_set_samplefrequency(handle, index, signal.samples_per_record), "a rate");
    edf_test_check(edf_set_physical_minimum(handle, index, signal.physical_min), "a minimum");
    edf_test_check(edf_set_physical_maximum(handle, index, signal.physical_max), "a maximum");
    edf_test_check(edf_set_digital_minimum(handle, index, signal.digital_min), "a digital minimum");
    edf_test_check(edf_set_digital_maximum(handle, index, signal.digital_max), "a digital maximum");
    edf_test_check(edf_set_label(handle, index, signal.label.c_str()), "a label");
    edf_test_check(edf_set_physical_dimension(handle, index, signal.unit.c_str()), "a unit");
  }
  if (spec.header_fields) {
    edf_test_check(edf_set_startdatetime(handle, 2024, 3, 5, 14, 7, 9), "the start");
    edf_test_check(edf_set_subsecond_starttime(handle, 2500000), "the start's fraction");
    edf_test_check(edf_set_patientcode(handle, "P-017"), "the patient code");
    edf_test_check(edf_set_patientname(handle, "Doe_Jane"), "the patient name");
    edf_test_check(edf_set_gender(handle, 0), "the sex");
    edf_test_check(edf_set_birthdate(handle, 1990, 7, 21), "the birth date");
    edf_test_check(edf_set_technician(handle, "Lab tech"), "the technician");
    edf_test_check(edf_set_equipment(handle, "TouchRig 2"), "the equipment");
    edf_test_check(edf_set_recording_additional(handle, "forearm session"), "the recording");
  }
  std::vector<long long> written(spec.signals.size(), 0);
  for (int record = 0; record < spec.records; ++record) {
    for (size_t k = 0; k < spec.signals.size(); ++k) {
      std::vector<int> values(static_cast<size_t>(spec.signals[k].samples_per_record));
      for (int& value : values)
        value = edf_test_digital(spec.signals[k], static_cast<int>(k), written[k]++);
      edf_test_check(edfwrite_digital_samples(handle, values.data()), "samples");
    }
  }
  for (const EdfTestAnnotation& annotation : spec.annotations)
    edf_test_check(edfwrite_annotation_utf8(
                       handle, std::llround(annotation.onset * 10000),
                       annotation.duration < 0 ? -1 : std::llround(annotation.duration * 10000),
                       annotation.text.c_str()),
                   "an annotation");
  edf_test_check(edfclose_file(handle), "closing");
}

// The EDF+ fixture: four signals at 100 Hz (Fz, Cz, Pz, Oz in uV), one at 25 Hz (Resp), three
// records of a second, and three annotations (two with durations, one without).
inline EdfTestFile edf_test_plus_file() {
  EdfTestFile spec;
  for (const char* label : {"Fz", "Cz", "Pz", "Oz"})
    spec.signals.push_back({label, 100, -500.0, 500.0, -32768, 32767, "uV"});
  spec.signals.push_back({"Resp", 25, -100.0, 100.0, -2048, 2047, "mV"});
  spec.records = 3;
  spec.annotations = {{0.5, 0.25, "Tap"}, {1.2, 0.8, "Stroke"}, {2.0, -1.0, "  Pat  "}};
  return spec;
}

// The BDF+ fixture: two 24-bit signals at 64 Hz (records of half a second), two annotations.
inline EdfTestFile edf_test_bdf_file() {
  EdfTestFile spec;
  spec.bdf = true;
  spec.signals.push_back({"Force", 32, -50.0, 50.0, -8388608, 8388607, "N"});
  spec.signals.push_back({"Shear", 32, -20.0, 20.0, -8388608, 8388607, "N"});
  spec.records = 4;
  spec.record_seconds = 0.5;
  spec.annotations = {{0.25, 0.5, "Press"}, {1.0, 0.5, "Slide"}};
  return spec;
}

}  // namespace tactile::testing
