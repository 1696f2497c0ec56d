#!/usr/bin/python3
"""Tree ensembles against their references (issue 26, part 4): random-forest vs scikit-learn's
RandomForestClassifier, bagged-trees vs BaggingClassifier(DecisionTreeClassifier(), 30),
boosted-trees vs XGBClassifier (python3-xgboost; the same library as ours) on the same
stratified folds, at the table shapes of shapes.py and optionally a wide one. Ensembles are
random: accuracy and time are the mean over --seeds seeds on each side. Both sides fit on
every core (our trees / XGBoost's nthread; scikit-learn n_jobs=2); folds run one at a time.
Writes ENSEMBLES.md.

    apt-get install -y python3-sklearn python3-xgboost
    /usr/bin/python3 bench/compare/shapes.py --out /tmp/shapes
    /usr/bin/python3 bench/compare/ensembles.py --tactile build/bin/tactile \\
        --features 5000x16=/tmp/shapes/5000x16.csv 1000x1200=/tmp/shapes/1000x1200.csv \\
                   20000x30=/tmp/shapes/20000x30.csv --wide 1100x13000 \\
        --out bench/compare/ENSEMBLES.md
"""
import argparse
import csv
import json
import os
import platform
import sys
import tempfile
import warnings

import numpy as np
from sklearn.model_selection import StratifiedKFold

import compare
import reference
import speed

ROWS = ["random-forest", "bagged-trees", "boosted-trees"]


def write_wide(path, rows, columns, seed=4):
    """A per-taxel style table: few informative columns among many (mostly quiet) ones, as
    generic features of a large grid give. 5 classes."""
    random = np.random.default_rng(seed)
    labels = np.arange(rows) % 5
    x = random.normal(0.0, 1.0, (rows, columns)) * (random.random((rows, columns)) < 0.2)
    informative = random.choice(columns, 40, replace=False)
    centres = random.normal(0.0, 1.0, (5, 40))
    x[:, informative] += centres[labels] * 1.5
    names = ["tap", "press", "pat", "stroke", "slap"]
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow([f"f{k}" for k in range(columns)] +
                        ["class", "subject", "recording", "segment_id"])
        for row in range(rows):
            writer.writerow([f"{v:.6g}" for v in x[row]] +
                            [names[labels[row]], f"s{row % 5}", f"r{row % 7}", row + 1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tactile", default="build/bin/tactile")
    parser.add_argument("--features", nargs="*", default=[], help="NAME=FILE.csv ...")
    parser.add_argument("--wide", help="also a generated ROWSxCOLUMNS table, e.g. 1100x13000")
    parser.add_argument("--folds", type=int, default=5)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--only", nargs="*", help="row names (default: the three ensembles)")
    parser.add_argument("--out", default="bench/compare/ENSEMBLES.md")
    parser.add_argument("--raw", help="also write the rows as JSON here")
    args = parser.parse_args()
    warnings.filterwarnings("ignore")
    names = args.only or ROWS
    pairs = [p for p in reference.pairs() if p.name in names]
    rows = []
    with tempfile.TemporaryDirectory(prefix="tactile-ensembles-") as scratch:
        tables = list(args.features)
        if args.wide:
            shape = [int(v) for v in args.wide.split("x")]
            path = os.path.join(scratch, f"{args.wide}.csv")
            write_wide(path, shape[0], shape[1])
            tables.append(f"{args.wide}={path}")
        for item in tables:
            dataset, _, path = item.partition("=")
            header, body, x, labels = compare.read_features(path)
            splitter = StratifiedKFold(n_splits=args.folds, shuffle=True, random_state=args.seed)
            folds = np.zeros(len(labels), dtype=int)
            for number, (_, test) in enumerate(splitter.split(x, labels)):
                folds[test] = number + 1
            fold_csv = os.path.join(scratch, f"{dataset}-folds.csv")
            compare.write_fold_csv(header, body, folds, fold_csv)
            for pair in pairs:
                seeds = range(args.seed, args.seed + args.seeds)
                ours_runs = [speed.run_ours(args.tactile, fold_csv, pair.ours, s, 1) for s in seeds]
                theirs_runs = [compare.cross_validate(lambda: pair.make(s, x.shape[1]), x, labels,
                                                      folds) for s in seeds]
                row = {"dataset": dataset, "rows": len(labels), "features": x.shape[1],
                       "classes": len(np.unique(labels)), "classifier": pair.name,
                       "reference": pair.describe, "seeds": args.seeds,
                       "ours": float(np.mean([r[0] for r in ours_runs])),
                       "sklearn": float(np.mean([r[0] for r in theirs_runs])),
                       "ours_seconds": float(np.mean([r[1] for r in ours_runs])),
                       "sklearn_seconds": float(np.mean([r[1] for r in theirs_runs])),
                       "ours_each": [r[0] for r in ours_runs],
                       "sklearn_each": [r[0] for r in theirs_runs]}
                rows.append(row)
                print(f"{dataset:10s} {pair.name:14s} ours {row['ours']:.4f} sklearn "
                      f"{row['sklearn']:.4f}  {row['ours_seconds']:.2f} s vs "
                      f"{row['sklearn_seconds']:.2f} s", file=sys.stderr, flush=True)
    if args.raw:
        with open(args.raw, "w") as handle:
            json.dump(rows, handle, indent=1)
    write(rows, args)


def write(rows, args):
    lines = ["# Tree ensembles against scikit-learn and XGBoost", "",
             f"Stratified {args.folds}-fold cross-validation on the same folds on both sides "
             f"(StratifiedKFold, shuffle, random_state={args.seed}; ours through `--protocol "
             f"loso` on a fold column, one fold at a time), mean over {args.seeds} seeds on "
             f"each side, one run on this machine ({os.cpu_count()} cores, "
             f"{platform.machine()}). Both sides fit on every core. Time = fit + predict "
             "summed over the folds; ratio = ours / reference (below 1: ours is faster).", ""]

    def line(r):
        difference = 100.0 * (r["ours"] - r["sklearn"])
        ratio = r["ours_seconds"] / r["sklearn_seconds"] if r["sklearn_seconds"] > 0 else 0.0
        return (f"| {r['classifier']} | {r['reference']} | {100 * r['ours']:.2f} | "
                f"{100 * r['sklearn']:.2f} | {difference:+.2f} | "
                f"{r['ours_seconds']:.2f} | {r['sklearn_seconds']:.2f} | {ratio:.2f} |")

    reference.write_dataset_tables(
        args.out, lines, rows,
        ["| classifier | reference | ours % | reference % | diff (pts) | ours s | reference s | "
         "time ours/reference |", "|---|---|---:|---:|---:|---:|---:|---:|"], line)


if __name__ == "__main__":
    main()
