#!/usr/bin/python3
"""Parity with scikit-learn, kept as a test (issue 26): every SVM, k-NN and tree preset, ours
(`tactile evaluate --protocol group:fold`) against scikit-learn (PredefinedSplit) on the same
folds, at every table shape; exits 1 when a checked row differs by more than --tolerance points.

    cmake --build build --target tactile
    /usr/bin/python3 bench/compare/parity.py --tactile build/bin/tactile --work /tmp/parity \\
        --out bench/compare/PARITY.md

Both sides run as whole processes (start to exit: reading the CSV, standardising, every fold),
and their wall times are compared. Ours prints its plain report (no --json: no per-row scores,
so the SVM fits no Platt sigmoids, as scikit-learn's SVC() fits none); the row
"medium-gaussian-svm, probabilities" runs ours with --json (per-row scores: the sigmoids)
against SVC(probability=True). Rows drawn at random on both sides (the 'auto' kernel scale's
draw of 100 points per class, subspace-knn's subspaces) are shown for information and not
checked. The tree rows are checked against the mean of scikit-learn over --tree-seeds values of
random_state (its order of trying features, which decides between equally good splits), the
spread shown. See README.md ("Parity").
"""
import argparse
import json
import os
import platform
import re
import resource
import subprocess
import sys
import time

import numpy as np
from sklearn.model_selection import StratifiedKFold

import shapes

HERE = os.path.dirname(os.path.abspath(__file__))

# (row name, our classifier, checked: deterministic on both sides)
ROWS = [
    ("linear-svm", "linear-svm", True),
    ("quadratic-svm (scale sqrtP)", "quadratic-svm:scale=sqrtP", True),
    ("cubic-svm (scale sqrtP)", "cubic-svm:scale=sqrtP", True),
    ("quadratic-svm (auto)", "quadratic-svm", False),
    ("cubic-svm (auto)", "cubic-svm", False),
    ("fine-gaussian-svm", "fine-gaussian-svm", True),
    ("medium-gaussian-svm", "medium-gaussian-svm", True),
    ("coarse-gaussian-svm", "coarse-gaussian-svm", True),
    ("rbf C=100 gamma=1/P", "medium-gaussian-svm:c=100", True),
    # The same model, timed both ways: ours computes class probabilities by default (five
    # more trainings per pair, libsvm's -b 1); scikit-learn's SVC does not.
    ("medium-gaussian-svm, votes only", "medium-gaussian-svm:probability=false", True),
    ("medium-gaussian-svm, probabilities", "medium-gaussian-svm", True),
    ("balanced rbf", "medium-gaussian-svm:weights=balanced", True),
    ("knn (k=1)", "knn", True),
    ("knn (k=10, standardised)", "knn:k=10,standardize=true", True),
    ("cosine-knn", "cosine-knn", True),
    ("weighted-knn", "weighted-knn", True),
    ("subspace-knn", "subspace-knn", False),
    ("tree", "tree", True),
    ("medium-tree", "medium-tree", True),
]
# Rows whose scores ours reports (--json): the SVM fits its Platt sigmoids, as
# SVC(probability=True) does.
SCORED_ROWS = {"medium-gaussian-svm, probabilities"}
TREE_ROWS = {"tree", "medium-tree"}


def imbalanced(rows, features, shares, seed):
    """Overlapping Gaussian classes with the given class shares (60/25/10/5 %)."""
    random = np.random.default_rng(seed)
    centres = random.normal(0.0, 1.0, (len(shares), features))
    counts = np.round(np.array(shares) * rows).astype(int)
    labels = np.repeat(np.arange(len(shares)), counts)
    labels = labels[random.permutation(len(labels))]
    # Class indices in order of first appearance, so that our class order (first seen) and
    # scikit-learn's (sorted names) agree, and so do both tie rules (lowest class).
    first_seen = {label: rank for rank, label in enumerate(dict.fromkeys(labels.tolist()))}
    labels = np.array([first_seen[label] for label in labels])
    x = centres[labels] + random.normal(0.0, 1.0, (len(labels), features))
    x *= np.exp(random.uniform(-2.0, 3.0, features))
    return x, labels


def capture(rows, channels, samples, seed):
    """Raw captures of a 12-electrode strip, channels x samples per row (channel-major):
    five touch types at one of three places along the strip, each channel seeing the touch through
    a Gaussian spatial gain; a stroke moves along the strip, a pat is two pulses, a tickle
    flickers, a slap is short and strong. Noise and a per-channel offset on every sample."""
    random = np.random.default_rng(seed)
    t = np.linspace(0.0, 1.0, samples)
    electrodes = np.arange(channels)[:, None]
    labels = np.arange(rows) % 5
    x = np.empty((rows, channels * samples))
    for row, label in enumerate(labels):
        onset, width = random.uniform(0.15, 0.3), random.uniform(0.08, 0.12)
        amplitude = random.uniform(0.6, 1.4)
        place = random.choice([3.0, 6.0, 9.0]) + random.normal(0.0, 0.3)
        spread = random.uniform(1.0, 2.5)
        time_course = np.exp(-0.5 * ((t - onset - width) / (0.5 * width)) ** 2)
        position = np.full(samples, place)
        if label == 1:  # press: long
            time_course = 1.0 / (1.0 + np.exp(-(t - onset) / 0.02)) * \
                (1.0 - 1.0 / (1.0 + np.exp(-(t - onset - 4 * width) / 0.02)))
        elif label == 2:  # pat: two pulses
            time_course += np.exp(-0.5 * ((t - onset - 3.5 * width) / (0.5 * width)) ** 2)
        elif label == 3:  # stroke: moves along the strip
            time_course = np.exp(-0.5 * ((t - onset - 2 * width) / (1.5 * width)) ** 2)
            position = place + random.choice([-1, 1]) * 6.0 * (t - onset)
        elif label == 4:  # tickle: flicker on a light touch
            time_course = 0.6 * time_course * (1.0 + 0.8 * np.sin(2 * np.pi * 30 * t))
        gain = np.exp(-0.5 * ((electrodes - position[None, :]) / spread) ** 2)
        signal = amplitude * gain * time_course[None, :]
        signal += random.normal(0.0, 0.12, (channels, samples))
        signal += random.normal(0.0, 0.2, (channels, 1))
        x[row] = signal.reshape(-1)
    return x, labels


def write_table(path, x, labels, names, folds):
    """Our CSV layout: features, class, subject, recording, segment_id, then the metadata
    column `fold` (read by `--protocol group:fold`)."""
    with open(path, "w") as handle:
        handle.write(",".join([f"f{k}" for k in range(x.shape[1])] +
                              ["class", "subject", "recording", "segment_id", "fold"]) + "\n")
        for row in range(x.shape[0]):
            handle.write(",".join(repr(float(v)) for v in x[row]) +
                         f",{names[labels[row]]},s{row % 5},r{row % 7},{row + 1},"
                         f"{folds[row]}\n")


def tables(args):
    """name -> (path, rows, features, classes), written once into --work."""
    # Sorted names: class k is both our k-th class (first seen, rows cycle through the
    # classes) and scikit-learn's (sorted), so ties go to the same class on both sides.
    gestures = ["pat", "press", "slap", "stroke", "tap", "tickle"]
    makers = {
        "5000x16": lambda: shapes.blobs(5000, 16, 5, 1, 1.1),
        f"{args.large_rows}x30": lambda: shapes.blobs(args.large_rows, 30, 6, 3, 2.2),
        "1000x1200": lambda: shapes.waveforms(1000, 1200, 2),
        "imbalanced 4000x16": lambda: imbalanced(4000, 16, [0.60, 0.25, 0.10, 0.05], 4),
        "capture 1100x12x100": lambda: capture(1100, 12, 100, 5),
    }
    result = {}
    for name, make in makers.items():
        if args.tables and name.split(" ")[0] not in args.tables and name not in args.tables:
            continue
        path = os.path.join(args.work, name.replace(" ", "-") + ".csv")
        x, labels = make()
        splitter = StratifiedKFold(n_splits=args.folds, shuffle=True, random_state=args.seed)
        folds = np.zeros(len(labels), dtype=int)
        for number, (_, test) in enumerate(splitter.split(x, labels)):
            folds[test] = number + 1
        if not os.path.exists(path):
            write_table(path + ".tmp", x, labels, gestures, folds)
            os.replace(path + ".tmp", path)
        result[name] = (path, x.shape[0], x.shape[1], len(np.unique(labels)))
    return result


def timed(command):
    """(result, wall seconds); the child's CPU seconds (user + sys) go into result["cpu"]."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: {done.stderr.strip()[-600:]}")
    if done.stdout.lstrip().startswith("{"):
        return {**json.loads(done.stdout), "cpu": cpu}, seconds
    # Our plain report: "accuracy    0.9322 (4661/5000 predictions, 93.22 %)".
    found = re.search(r"^accuracy\s+\S+ \((\d+)/(\d+) predictions", done.stdout, re.M)
    if not found:
        raise RuntimeError(f"{' '.join(command)}: no accuracy in {done.stdout[:300]!r}")
    return {"accuracy": int(found.group(1)) / int(found.group(2)), "cpu": cpu}, seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tactile", default="build/bin/tactile")
    parser.add_argument("--work", default="/tmp/parity", help="folder for the tables")
    parser.add_argument("--folds", type=int, default=5)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--large-rows", type=int, default=20000,
                        help="rows of the large 30-feature table (default 20000)")
    parser.add_argument("--threads", type=int, default=0, help="ours: --threads (0: every core)")
    parser.add_argument("--tolerance", type=float, default=0.3, help="points")
    parser.add_argument("--tree-seeds", type=int, default=6,
                        help="tree rows: scikit-learn's mean over this many random_state values")
    parser.add_argument("--tables", nargs="*", help="table names (default: all)")
    parser.add_argument("--only", nargs="*", help="row names (default: all)")
    parser.add_argument("--out", help="write the markdown table here (PARITY.md)")
    parser.add_argument("--raw", help="also write the rows as JSON here")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    rows = []
    for table, (path, count, features, classes) in tables(args).items():
        for name, ours_spec, checked in ROWS:
            if args.only and name not in args.only:
                continue
            ours, ours_seconds = timed(
                [args.tactile, "evaluate", "--features", path, "--classifier", ours_spec,
                 "--protocol", "group:fold", "--seed", str(args.seed), "--threads",
                 str(args.threads)] + (["--json"] if name in SCORED_ROWS else []))
            theirs, theirs_seconds = timed(
                [sys.executable, os.path.join(HERE, "parity_sklearn.py"), "--features", path,
                 "--row", name, "--seed", str(args.seed)] +
                (["--seeds", str(args.tree_seeds)] if name in TREE_ROWS else []))
            difference = 100.0 * (ours["accuracy"] - theirs["accuracy"])
            row = {"table": table, "rows": count, "features": features, "classes": classes,
                   "classifier": name, "ours_spec": ours_spec, "checked": checked,
                   "ours": ours["accuracy"], "sklearn": theirs["accuracy"],
                   "sklearn_plain": theirs["plain"], "difference": difference,
                   "ours_seconds": ours_seconds, "sklearn_seconds": theirs_seconds,
                   "sklearn_seeds": theirs.get("seeds", []),
                   "ours_cpu": ours["cpu"], "sklearn_cpu": theirs["cpu"],
                   "pass": not checked or abs(difference) <= args.tolerance}
            rows.append(row)
            print(f"{table:20s} {name:28s} ours {100 * row['ours']:6.2f} sklearn "
                  f"{100 * row['sklearn']:6.2f} ({100 * row['sklearn_plain']:6.2f} own rule) "
                  f"{difference:+5.2f}  {ours_seconds:7.2f} s vs {theirs_seconds:7.2f} s "
                  f"{theirs_seconds / ours_seconds:5.2f}x  CPU {ours['cpu']:6.2f} vs "
                  f"{theirs['cpu']:6.2f} {theirs['cpu'] / max(ours['cpu'], 1e-9):5.2f}x  "
                  f"{'ok' if row['pass'] else 'MISSED'}{'' if checked else ' (random)'}"
                  f"{spread(row)}", flush=True)
            if args.raw:  # after every row, so that a stopped run keeps what it measured
                with open(args.raw, "w") as handle:
                    json.dump(rows, handle, indent=1)
    if args.out:
        write_markdown(rows, args)
    missed = [r for r in rows if not r["pass"]]
    for r in missed:
        print(f"MISSED: {r['table']} {r['classifier']}: {r['difference']:+.2f} points",
              file=sys.stderr)
    return 1 if missed else 0


def spread(row):
    """' (sklearn over N seeds: lo-hi)' for rows checked against a mean over seeds."""
    seeds = row.get("sklearn_seeds", [])
    if len(seeds) < 2:
        return ""
    return (f" (sklearn over {len(seeds)} seeds: {100 * min(seeds):.2f}-"
            f"{100 * max(seeds):.2f})")


def write_markdown(rows, args):
    lines = [
        "# Parity with scikit-learn (bench/compare/parity.py)", "",
        f"Stratified {args.folds}-fold cross-validation (StratifiedKFold, shuffle, random_state="
        f"{args.seed}), the fold written into each table as the metadata column `fold`: ours "
        "`tactile evaluate --protocol group:fold`, scikit-learn `PredefinedSplit` on the same "
        "column (parity_sklearn.py). Standardisation inside the fold on both sides (sample "
        "deviation). Times are whole processes, start to exit (reading the CSV included; "
        "ours with `--threads "
        f"{args.threads}`{' = every core' if args.threads == 0 else ''}, its plain report: no "
        "per-row scores, so no SVM sigmoids, except the probabilities row (--json) against "
        "SVC(probability=True); scikit-learn's SVC single-threaded as it is; CPU = user + sys "
        "of the process), one run on this machine "
        f"({os.cpu_count()} cores, {platform.machine()}); ratio = scikit-learn's seconds / ours. "
        f"A checked row passes when |diff| <= {args.tolerance} points; rows marked random draw "
        "at random on both sides and are shown, not checked. k-NN rows: the reference is "
        "scikit-learn's neighbours with our tie rule (nearest neighbour among tied classes); "
        "scikit-learn's own rule (lowest label) in the last column. Tree rows: against "
        f"scikit-learn's mean over random_state {args.seed}..{args.seed + args.tree_seeds - 1} "
        "(its tie order between equally good splits), the spread shown.", "",
        "| shape | classifier | ours % | sklearn % | diff | ours s | sklearn s | ratio | "
        "ours CPU s | sklearn CPU s | CPU ratio | check | sklearn own rule % |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|"]
    for r in rows:
        check = ("ok" if r["pass"] else "**missed**") if r["checked"] else "random"
        lines.append(
            f"| {r['table']} | {r['classifier']} | {100 * r['ours']:.2f} | "
            f"{100 * r['sklearn']:.2f} | {r['difference']:+.2f} | {r['ours_seconds']:.2f} | "
            f"{r['sklearn_seconds']:.2f} | {r['sklearn_seconds'] / r['ours_seconds']:.2f}x | "
            f"{r['ours_cpu']:.2f} | {r['sklearn_cpu']:.2f} | "
            f"{r['sklearn_cpu'] / max(r['ours_cpu'], 1e-9):.2f}x | "
            f"{check}{spread(r)} | {100 * r['sklearn_plain']:.2f} |")
    lines.append("")
    with open(args.out + ".tmp", "w") as handle:
        handle.write("\n".join(lines))
    os.replace(args.out + ".tmp", args.out)


if __name__ == "__main__":
    sys.exit(main())
