#!/usr/bin/python3
"""The generic pipeline on capture-style data (issue "Other people's data", part 2): many
published tactile sets are fixed-length windows of a few channels with a class each. This
exports simulated TSA, flux and fur touches in that shape (a channel per body location of
TSA and per row of the fur matrix, summed over their taxels; flux's 8 coils; a fixed window
from each ground-truth touch's start), imports them with `tactile import
--wide`, and compares on the same stratified folds:

  ours        `tactile features --pipeline generic` + `tactile evaluate --classifier auto`
  raw SVM     scikit-learn's RBF SVM (standardised, C=1, gamma=scale) on the raw samples
  SVM on ours the same SVM on our generic features

Goal: ours ahead of the raw-sample SVM by >= 3 points on every set. Writes GENERIC.md.

    /usr/bin/python3 bench/compare/generic.py --tactile build/bin/tactile --work /tmp/generic \\
        --out bench/compare/GENERIC.md
"""
import argparse
import csv
import json
import os
import sqlite3
import subprocess

import h5py
import numpy as np
from sklearn.model_selection import StratifiedKFold
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler
from sklearn.svm import SVC

import compare

# skin: (window seconds, keep every Nth sample, subjects, the layout groups summed into one
# channel each: "a few channels" as published sets have; None: the real channels)
SETS = {"tsa": (3.0, 1, 6, "location"), "fur": (3.0, 1, 6, "row"), "flux": (5.0, 10, 6, None)}
HERE = os.path.dirname(os.path.abspath(__file__))


def group_channels(skin, kind, names):
    """Per layout group of `kind`, the stream columns of its taxels."""
    with open(os.path.join(HERE, "..", "..", "assets", "layouts", skin + ".json")) as handle:
        layout = json.load(handle)
    channel_of = {taxel["id"]: list(taxel["channels"].values()) for taxel in layout["taxels"]}
    groups = []
    for group in layout["groups"]:
        if group.get("kind") != kind:
            continue
        columns = [names.index(c) for taxel in group["taxels"] for c in channel_of[taxel] if c in names]
        if columns:
            groups.append(columns)
    if not groups:
        raise SystemExit(f"{skin}: no layout groups of kind {kind}")
    return groups


def run(command):
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)}: {done.stderr.strip()}")
    return done.stdout


def captures(folder, skin, seconds, step, kind):
    """Fixed windows from each touch's start: [captures][channels][samples], classes."""
    db = sqlite3.connect(os.path.join(folder, "labels.db"))
    windows, classes = [], []
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".h5"):
            continue
        with h5py.File(os.path.join(folder, name), "r") as f:
            group = f["streams/skin"]
            samples = group["samples"][:]  # [channels][samples]
            names = [c.decode() for c in group["channels"][:]]
            rate = float(group.attrs["rate_hz"])
            start = float(group.attrs["start_time"])
        if kind is None:  # the real channels (flux's sums are preprocessing's)
            samples = samples[[k for k, n in enumerate(names) if not n.endswith("_sum")]]
        else:
            samples = np.array([samples[columns].sum(axis=0) for columns in group_channels(skin, kind, names)])
        length = int(round(seconds * rate))
        rows = db.execute("select t0, class from labels where recording = ? and source = 'ground-truth' "
                          "order by t0", (name[:-3],)).fetchall()
        for t0, label in rows:
            first = int(round((t0 - start) * rate))
            if first < 0 or first + length > samples.shape[1]:
                continue
            window = samples[:, first:first + length]
            if step > 1:  # average each run of `step` samples (a lower rate)
                window = window[:, :length // step * step].reshape(window.shape[0], -1, step).mean(axis=2)
            windows.append(window)
            classes.append(label)
    return np.array(windows), np.array(classes), rate / step


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tactile", default="build/bin/tactile")
    parser.add_argument("--work", required=True)
    parser.add_argument("--out", default="bench/compare/GENERIC.md")
    parser.add_argument("--folds", type=int, default=5)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    lines = []
    for skin, (seconds, step, subjects, kind) in SETS.items():
        folder = os.path.join(args.work, skin)
        if not os.path.exists(os.path.join(folder, "labels.db")):
            run([args.tactile, "simulate", "--skin", skin, "--subjects", str(subjects), "--trials", "1",
                 "--seed", str(args.seed), "--out", folder])
        x, labels, rate = captures(folder, skin, seconds, step, kind)
        n, c, s = x.shape
        wide = os.path.join(args.work, f"{skin}-captures.csv")
        with open(wide, "w", newline="") as handle:
            csv.writer(handle).writerows(x.reshape(n, c * s).tolist())
        label_file = os.path.join(args.work, f"{skin}-classes.txt")
        with open(label_file, "w") as handle:
            handle.write("\n".join(labels) + "\n")
        database = os.path.join(args.work, f"{skin}-captures.db")
        recording = os.path.join(args.work, f"{skin}-captures.h5")
        for path in (database, recording):
            if os.path.exists(path):
                os.remove(path)
        run([args.tactile, "import", wide, "--wide", "--layout", f"strip:{c}", "--samples-per-capture", str(s),
             "--labels-file", label_file, "--class-names", ",".join(sorted(set(labels))), "--rate", str(rate),
             "--out", recording, "--labels", database])
        features = os.path.join(args.work, f"{skin}-generic.csv")
        run([args.tactile, "features", "--pipeline", "generic", "--params", "modality=all", "--labels", database,
             "--out", features])
        header, body, ours_x, ours_labels = compare.read_features(features)
        if list(ours_labels) != list(labels):
            raise SystemExit(f"{skin}: the feature rows are not the captures in order")
        splitter = StratifiedKFold(n_splits=args.folds, shuffle=True, random_state=args.seed)
        folds = np.zeros(n, dtype=int)
        for number, (_, test) in enumerate(splitter.split(np.zeros(n), labels)):
            folds[test] = number + 1
        fold_csv = os.path.join(args.work, f"{skin}-generic-folds.csv")
        compare.write_fold_csv(header, body, folds, fold_csv)
        ours, *_ = compare.run_ours(args.tactile, fold_csv, "auto", args.seed)

        def svm():
            return make_pipeline(StandardScaler(), SVC(C=1.0, gamma="scale"))

        raw, _ = compare.cross_validate(lambda: svm(), x.reshape(n, c * s), labels, folds)
        on_ours, _ = compare.cross_validate(lambda: svm(), ours_x, labels, folds)
        margin = 100 * (ours - raw)
        lines.append(f"| {skin} | {n} x {c} x {s} ({rate:g} Hz) | {len(set(labels))} | {100 * ours:.1f} | "
                     f"{100 * raw:.1f} | {100 * on_ours:.1f} | {margin:+.1f} | {'met' if margin >= 3 else 'not met'} |")
        print(lines[-1], flush=True)
    with open(args.out, "w") as handle:
        handle.write("# The generic pipeline on capture-style data\n\n"
                     "Simulated touches exported as published capture sets are: fixed windows from each "
                     "ground-truth touch's start; a channel per TSA body location and per fur matrix row (the sum of "
                     "their taxels), flux's 8 coils (`bench/compare/generic.py`). "
                     f"Stratified {args.folds}-fold cross-validation, the same folds on every side "
                     f"(seed {args.seed}); accuracy in %.\n\n"
                     "| set | captures x channels x samples | classes | generic + auto (ours) | "
                     "RBF SVM, raw samples | RBF SVM, our features | ours - raw (pts) | goal >= +3 |\n"
                     "|---|---|---:|---:|---:|---:|---:|---|\n" + "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
