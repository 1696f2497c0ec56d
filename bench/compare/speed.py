#!/usr/bin/python3
"""Speed of `tactile evaluate` against scikit-learn at three table shapes (issue "Classifiers
in the workbench", part 5): every SVM and k-NN row of reference.py on the same stratified
folds, accuracy side by side, times as speed-ups (scikit-learn's seconds / ours). Ours is
timed on one thread (as scikit-learn's cross-validation loop runs by default) and on every
core (our default: folds on worker threads). Writes SPEED.md.

    /usr/bin/python3 bench/compare/shapes.py --out /tmp/shapes
    /usr/bin/python3 bench/compare/speed.py --tactile build/bin/tactile \\
        --features 5000x16=/tmp/shapes/5000x16.csv 1000x1200=/tmp/shapes/1000x1200.csv \\
                   20000x30=/tmp/shapes/20000x30.csv --out bench/compare/SPEED.md
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np
from sklearn.model_selection import StratifiedKFold

import compare
import reference

ROWS = ["linear-svm", "quadratic-svm (scale sqrtP)", "quadratic-svm (auto)",
        "cubic-svm (scale sqrtP)", "cubic-svm (auto)", "fine-gaussian-svm",
        "medium-gaussian-svm", "coarse-gaussian-svm", "knn (k=1)",
        "knn (k=10, standardised)", "cosine-knn", "weighted-knn"]


def run_ours(binary, csv_path, specification, seed, threads):
    command = [binary, "evaluate", "--features", csv_path, "--classifier", specification,
               "--protocol", "loso", "--seed", str(seed), "--threads", str(threads), "--json"]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: {done.stderr.strip()}")
    result = json.loads(done.stdout)
    return result["accuracy"], result["seconds"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tactile", default="build/bin/tactile")
    parser.add_argument("--features", nargs="+", required=True, help="NAME=FILE.csv ...")
    parser.add_argument("--folds", type=int, default=5)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--only", nargs="*", help="row names (default: every SVM and k-NN row)")
    parser.add_argument("--out", default="bench/compare/SPEED.md")
    parser.add_argument("--raw", help="also write the rows as JSON here")
    args = parser.parse_args()
    warnings.filterwarnings("ignore")
    names = args.only or ROWS
    pairs = [p for p in reference.pairs() if p.name in names]
    rows = []
    with tempfile.TemporaryDirectory(prefix="tactile-speed-") as scratch:
        for item in args.features:
            dataset, _, path = item.partition("=")
            header, body, x, labels = compare.read_features(path)
            splitter = StratifiedKFold(n_splits=args.folds, shuffle=True, random_state=args.seed)
            folds = np.zeros(len(labels), dtype=int)
            for number, (_, test) in enumerate(splitter.split(x, labels)):
                folds[test] = number + 1
            fold_csv = os.path.join(scratch, f"{dataset}-folds.csv")
            compare.write_fold_csv(header, body, folds, fold_csv)
            for pair in pairs:
                ours, ours_seconds = run_ours(args.tactile, fold_csv, pair.ours, args.seed, 1)
                _, ours_all = run_ours(args.tactile, fold_csv, pair.ours, args.seed, 0)
                theirs, theirs_seconds = compare.cross_validate(
                    lambda: pair.make(args.seed, x.shape[1]), x, labels, folds)
                row = {"dataset": dataset, "rows": len(labels), "features": x.shape[1],
                       "classes": len(np.unique(labels)), "classifier": pair.name,
                       "reference": pair.describe, "ours": ours, "sklearn": theirs,
                       "ours_seconds": ours_seconds, "ours_all_cores_seconds": ours_all,
                       "sklearn_seconds": theirs_seconds}
                rows.append(row)
                print(f"{dataset:9s} {pair.name:28s} ours {ours:.4f} sklearn {theirs:.4f}  "
                      f"{ours_seconds:.3f} s ({ours_all:.3f} s all cores) vs {theirs_seconds:.3f} s",
                      file=sys.stderr, flush=True)
    if args.raw:
        with open(args.raw, "w") as handle:
            json.dump(rows, handle, indent=1)
    write(rows, args)


def write(rows, args):
    lines = ["# Speed against scikit-learn at three table shapes", "",
             f"Stratified {args.folds}-fold cross-validation on the same folds on both sides "
             f"(scikit-learn StratifiedKFold, shuffle, random_state={args.seed}; ours through "
             "`--protocol loso` on a fold column), one run on this machine "
             f"({os.cpu_count()} cores, {platform.machine()}). Time = fit + predict summed over "
             "the folds. Speed-up = scikit-learn's seconds / ours: ours on one thread (as "
             "scikit-learn's loop runs), and ours on every core (`tactile evaluate`'s default: "
             "folds on worker threads). Goal per row: accuracy within 1 point and speed-up >= 2.",
             "", "Tables: `bench/compare/shapes.py` (5000 x 16 and 20000 x 30: overlapping Gaussian "
             "classes in features of mixed units; 1000 x 1200: raw touch waveforms, 1200 samples "
             "a row).", ""]

    def line(r):
        difference = 100.0 * (r["ours"] - r["sklearn"])
        one = r["sklearn_seconds"] / r["ours_seconds"] if r["ours_seconds"] > 0 else 0.0
        every = (r["sklearn_seconds"] / r["ours_all_cores_seconds"]
                 if r["ours_all_cores_seconds"] > 0 else 0.0)
        accurate = abs(difference) <= 1.0
        goal = ("met" if accurate and one >= 2.0 else
                "met on all cores" if accurate and every >= 2.0 else
                "not met" + ("" if accurate else " (accuracy)"))
        return (f"| {r['classifier']} | {100 * r['ours']:.2f} | {100 * r['sklearn']:.2f} | "
                f"{difference:+.2f} | {r['ours_seconds']:.3f} | {r['sklearn_seconds']:.3f} | "
                f"{one:.2f}x | {r['ours_all_cores_seconds']:.3f} | {every:.2f}x | {goal} |")

    reference.write_dataset_tables(
        args.out, lines, rows,
        ["| classifier | ours % | sklearn % | diff (pts) | ours s (1 thread) | sklearn s | "
         "speed-up | ours s (all cores) | speed-up | goal |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"], line)


if __name__ == "__main__":
    main()
