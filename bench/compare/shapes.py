#!/usr/bin/python3
"""Feature tables of three shapes for the speed comparison (bench/compare/SPEED.md):
5000 x 16 and 20000 x 30 (overlapping Gaussian classes, as descriptor tables are) and
1000 x 1200 (long raw-sample rows: a touch's waveform, 1200 samples, of one of four
shapes with random onset, amplitude, width and noise). Deterministic (numpy seed).
Written in our CSV layout: features, then class, subject, recording, segment_id."""
import argparse
import csv
import os

import numpy as np


def blobs(rows, features, classes, seed, spread):
    random = np.random.default_rng(seed)
    centres = random.normal(0.0, 1.0, (classes, features))
    labels = np.arange(rows) % classes
    x = centres[labels] + random.normal(0.0, spread, (rows, features))
    # Features of different units, as real descriptors have.
    x *= np.exp(random.uniform(-2.0, 3.0, features))
    return x, labels


def waveforms(rows, samples, seed):
    random = np.random.default_rng(seed)
    t = np.linspace(0.0, 1.0, samples)
    labels = np.arange(rows) % 4
    x = np.empty((rows, samples))
    for row, label in enumerate(labels):
        onset = random.uniform(0.1, 0.5)
        width = random.uniform(0.05, 0.15) * (3.0 if label in (1, 3) else 1.0)
        amplitude = random.uniform(0.6, 1.4)
        pulse = np.exp(-0.5 * ((t - onset - width) / (0.4 * width)) ** 2)
        if label == 2:  # a pat: two pulses
            pulse += np.exp(-0.5 * ((t - onset - 3.5 * width) / (0.4 * width)) ** 2)
        if label == 3:  # a stroke: a ripple on a long press
            pulse *= 1.0 + 0.5 * np.sin(2 * np.pi * 25 * t)
        x[row] = amplitude * pulse + random.normal(0.0, 0.25, samples)
    return x, labels


def write(path, x, labels, names):
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow([f"f{k}" for k in range(x.shape[1])] +
                        ["class", "subject", "recording", "segment_id"])
        for row in range(x.shape[0]):
            writer.writerow([repr(float(v)) for v in x[row]] +
                            [names[labels[row]], f"s{row % 5}", f"r{row % 7}", row + 1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", required=True, help="folder for the three CSVs")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    gestures = ["tap", "press", "pat", "stroke", "slap", "tickle"]
    x, y = blobs(5000, 16, 5, 1, 1.1)
    write(os.path.join(args.out, "5000x16.csv"), x, y, gestures)
    x, y = waveforms(1000, 1200, 2)
    write(os.path.join(args.out, "1000x1200.csv"), x, y, gestures)
    x, y = blobs(20000, 30, 6, 3, 2.2)
    write(os.path.join(args.out, "20000x30.csv"), x, y, gestures)


if __name__ == "__main__":
    main()
