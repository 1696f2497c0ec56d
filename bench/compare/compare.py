#!/usr/bin/python3
"""Cross-validate our classifiers (`tactile evaluate`) and scikit-learn (and Weka where it has
the same algorithm) on the same feature CSV with the same stratified folds; write a markdown
table of accuracies, differences and wall-time ratios.

Folds: scikit-learn's StratifiedKFold draws them once per dataset. Our side gets them through
a copy of the CSV whose `subject` column holds the fold number, evaluated with
`--protocol loso` (leave-one-"subject"-out over that column = exactly those folds).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np
from sklearn.model_selection import StratifiedKFold

import reference

RESERVED = ("class", "subject", "recording", "segment_id")


def read_features(path):
    """Feature columns are the numeric columns before `class` (our CSV layout)."""
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    header, body = rows[0], rows[1:]
    if "class" not in header:
        raise SystemExit(f"{path}: no class column")
    class_column = header.index("class")
    try:
        x = np.array([[float(v) for v in row[:class_column]] for row in body])
    except ValueError as error:
        raise SystemExit(f"{path}: a feature cell is not a number ({error})")
    if not np.all(np.isfinite(x)):
        raise SystemExit(f"{path}: a feature is NaN or infinite")
    labels = np.array([row[class_column] for row in body])
    return header, body, x, labels


def write_fold_csv(header, body, folds, path):
    """The same rows with `subject` replaced by the fold number (added if missing)."""
    if "subject" in header:
        column = header.index("subject")
        header_out = header
        body_out = [row[:column] + [f"fold{folds[i]:02d}"] + row[column + 1:]
                    for i, row in enumerate(body)]
    else:
        column = header.index("class") + 1
        header_out = header[:column] + ["subject"] + header[column:]
        body_out = [row[:column] + [f"fold{folds[i]:02d}"] + row[column:]
                    for i, row in enumerate(body)]
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(header_out)
        writer.writerows(body_out)


def run_ours(binary, csv_path, specification, seed):
    command = [binary, "evaluate", "--features", csv_path, "--classifier", specification,
               "--protocol", "loso", "--seed", str(seed), "--threads", "1", "--json"]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: {done.stderr.strip()}")
    result = json.loads(done.stdout)
    return result["accuracy"], result["seconds"], wall, result.get("classifier", specification)


def cross_validate(make_model, x, labels, folds):
    """Accuracy and seconds (fit + predict summed over folds, like our `seconds`)."""
    correct, seconds = 0, 0.0
    for fold in np.unique(folds):
        test = folds == fold
        model = make_model()
        start = time.perf_counter()
        model.fit(x[~test], labels[~test])
        predicted = model.predict(x[test])
        seconds += time.perf_counter() - start
        correct += int(np.sum(predicted == labels[test]))
    return correct / len(labels), seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tactile", default="build/bin/tactile")
    parser.add_argument("--features", nargs="+", required=True, help="NAME=FILE.csv ...")
    parser.add_argument("--folds", type=int, default=10)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--only", nargs="*", help="classifier names to run (default: all)")
    parser.add_argument("--weka", default="/usr/share/java/weka.jar",
                        help="weka.jar ('' to skip Weka)")
    parser.add_argument("--out", default="bench/compare/RESULTS.md")
    parser.add_argument("--raw", help="also write the rows as JSON here")
    args = parser.parse_args()
    # Collinearity and convergence notices from scikit-learn: the table shows the outcome.
    warnings.filterwarnings("ignore")

    pairs = reference.pairs()
    if args.only:
        pairs = [p for p in pairs if p.name in args.only]
    rows = []
    with tempfile.TemporaryDirectory(prefix="tactile-compare-") as scratch:
        for item in args.features:
            dataset, _, path = item.partition("=")
            header, body, x, labels = read_features(path)
            splitter = StratifiedKFold(n_splits=args.folds, shuffle=True, random_state=args.seed)
            folds = np.zeros(len(labels), dtype=int)
            for number, (_, test) in enumerate(splitter.split(x, labels)):
                folds[test] = number + 1
            fold_csv = os.path.join(scratch, f"{dataset}-folds.csv")
            write_fold_csv(header, body, folds, fold_csv)
            weka_folds = None
            if args.weka and os.path.exists(args.weka):
                weka_folds = reference.write_weka_folds(x, labels, folds, scratch, dataset)
            for pair in pairs:
                # A randomised model (em) is run with several seeds on both sides and the
                # mean compared: one seed each compares two local optima, not two programs.
                seeds = range(args.seed, args.seed + pair.seeds)
                ours_runs = [run_ours(args.tactile, fold_csv, pair.ours, s) for s in seeds]
                theirs_runs = [cross_validate(lambda: pair.make(s, x.shape[1]), x, labels, folds)
                               for s in seeds]
                ours = float(np.mean([run[0] for run in ours_runs]))
                ours_seconds = float(np.mean([run[1] for run in ours_runs]))
                ours_wall = float(np.mean([run[2] for run in ours_runs]))
                effective = ours_runs[0][3]
                theirs = float(np.mean([run[0] for run in theirs_runs]))
                theirs_seconds = float(np.mean([run[1] for run in theirs_runs]))
                row = {"dataset": dataset, "rows": len(labels), "features": x.shape[1],
                       "classes": len(np.unique(labels)), "classifier": pair.name,
                       "ours_spec": effective, "reference": pair.describe,
                       "ours": ours, "ours_seconds": ours_seconds, "ours_wall": ours_wall,
                       "sklearn": theirs, "sklearn_seconds": theirs_seconds,
                       "seeds": pair.seeds,
                       "ours_each": [run[0] for run in ours_runs],
                       "sklearn_each": [run[0] for run in theirs_runs]}
                if weka_folds and pair.weka:
                    row["weka"], row["weka_seconds"] = reference.run_weka(
                        args.weka, pair.weka, weka_folds)
                    row["weka_scheme"] = pair.weka
                rows.append(row)
                weka_text = f" weka {row['weka']:.4f}" if "weka" in row else ""
                print(f"{dataset:6s} {pair.name:22s} ours {ours:.4f} sklearn {theirs:.4f}"
                      f"{weka_text}  ({ours_seconds:.3f} s vs {theirs_seconds:.3f} s)",
                      file=sys.stderr, flush=True)
    if args.raw:
        with open(args.raw, "w") as handle:
            json.dump(rows, handle, indent=1)
    reference.write_table(rows, args, args.out)


if __name__ == "__main__":
    main()
