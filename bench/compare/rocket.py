#!/usr/bin/python3
"""raw and rocket pipelines and the ridge classifier on every simulated skin (issue 26).

Part 1, every skin: `tactile simulate --skin S`, then `tactile features` with the skin's
paper pipeline, generic, raw and rocket, and `tactile evaluate --protocol loso --threads 1`
with a few classifiers per table. Columns: accuracy, seconds of the feature run and of the
evaluation (as `tactile evaluate` reports it: fit + predict summed over folds).

Part 2, ridge against scikit-learn: on each skin's rocket table (our transform's CSV), the
same StratifiedKFold(5, shuffle, random_state=1) folds for both (ours: a copy of the CSV
with a `fold` column and `--protocol group:fold`); scikit-learn's
RidgeClassifierCV(alphas=logspace(-3, 3, 10)) on columns z-scored on the training fold
with the sample deviation (n - 1), as our Standardizer. Time: ours as reported by
`tactile evaluate` (one thread), scikit-learn's fit + predict in this process.

    /usr/bin/python3 bench/compare/rocket.py --tactile build/bin/tactile --work /tmp/rocket \\
        --out bench/compare/ROCKET.md
"""
import argparse
import csv
import json
import os
import subprocess
import time

import numpy as np
from sklearn.linear_model import RidgeClassifierCV
from sklearn.model_selection import StratifiedKFold

PAPER = {"nao": "kaboli", "tsa": "tsa_event", "fur": "fur", "robovie": "robovie_xcorr", "flux": "flux"}
# (pipeline, classifier): the paper's table with a linear SVM and ridge; generic likewise;
# the raw-sample RBF SVM (the baseline of issue 26) and ridge on raw; ridge on rocket.
RUNS = [("paper", "linear-svm"), ("paper", "ridge"), ("generic", "linear-svm"), ("generic", "ridge"),
        ("raw", "medium-gaussian-svm"), ("raw", "ridge"), ("rocket", "ridge")]


class Failed(Exception):
    pass


def run(command):
    began = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise Failed(done.stderr.strip().splitlines()[-1] if done.stderr.strip() else f"exit {done.returncode}")
    return done.stdout, time.perf_counter() - began


def evaluate(tactile, table, classifier, protocol):
    out, _ = run([tactile, "evaluate", "--features", table, "--classifier", classifier,
                  "--protocol", protocol, "--threads", "1", "--json"])
    result = json.loads(out)
    return result["accuracy"], result["seconds"]


def read_table(path, prefix):
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    header = rows[0]
    features = [i for i, name in enumerate(header) if name.startswith(prefix)]
    label = header.index("class")
    x = np.array([[float(row[i]) for i in features] for row in rows[1:]])
    y = np.array([row[label] for row in rows[1:]])
    return header, rows[1:], x, y


def ridge_against_sklearn(tactile, table, work, skin):
    header, rows, x, y = read_table(table, "rocket.")
    folds = np.zeros(len(y), dtype=int)
    for fold, (_, test) in enumerate(StratifiedKFold(5, shuffle=True, random_state=1).split(x, y)):
        folds[test] = fold
    copy = os.path.join(work, f"{skin}-rocket-folds.csv")
    with open(copy, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(header + ["fold"])
        for row, fold in zip(rows, folds):
            writer.writerow(row + [f"f{fold}"])
    ours, ours_seconds = evaluate(tactile, copy, "ridge", "group:fold")
    correct, seconds = 0, 0.0
    for fold in range(5):
        train, test = folds != fold, folds == fold
        began = time.perf_counter()
        mean = x[train].mean(axis=0)
        scale = x[train].std(axis=0, ddof=1)
        scale[~(scale > 1e-12 * np.maximum(1.0, np.abs(mean)))] = 1.0
        model = RidgeClassifierCV(alphas=np.logspace(-3, 3, 10)).fit((x[train] - mean) / scale, y[train])
        predicted = model.predict((x[test] - mean) / scale)
        seconds += time.perf_counter() - began
        correct += int((predicted == y[test]).sum())
    return {"skin": skin, "rows": len(y), "columns": x.shape[1], "ours": ours, "ours_seconds": ours_seconds,
            "sklearn": correct / len(y), "sklearn_seconds": seconds}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tactile", default="build/bin/tactile")
    parser.add_argument("--work", default="/tmp/rocket")
    parser.add_argument("--out", default="bench/compare/ROCKET.md")
    parser.add_argument("--skins", nargs="*", default=list(PAPER))
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    results, versus = [], []
    for skin in args.skins:
        folder = os.path.join(args.work, skin)
        if not os.path.exists(os.path.join(folder, "labels.db")):
            run([args.tactile, "simulate", "--skin", skin, "--out", folder])
        tables, feature_seconds = {}, {}
        for kind in ["paper", "generic", "raw", "rocket"]:
            pipeline = PAPER[skin] if kind == "paper" else kind
            table = os.path.join(args.work, f"{skin}-{pipeline}.csv")
            try:
                _, feature_seconds[kind] = run([args.tactile, "features", "--pipeline", pipeline, "--threads", "1",
                                                "--labels", os.path.join(folder, "labels.db"), "--out", table])
                tables[kind] = table
            except Failed as failure:
                tables[kind] = str(failure)
        for kind, classifier in RUNS:
            pipeline = PAPER[skin] if kind == "paper" else kind
            if not tables[kind].endswith(".csv"):
                results.append({"skin": skin, "pipeline": pipeline, "classifier": classifier, "failed": tables[kind]})
                continue
            accuracy, seconds = evaluate(args.tactile, tables[kind], classifier, "loso")
            results.append({"skin": skin, "pipeline": pipeline, "classifier": classifier, "accuracy": accuracy,
                            "feature_seconds": feature_seconds[kind], "evaluate_seconds": seconds})
            print(results[-1], flush=True)
        versus.append(ridge_against_sklearn(args.tactile, tables["rocket"], args.work, skin))
        print(versus[-1], flush=True)
    # --skins reruns some skins: the others' rows are kept from the last run's JSON.
    raw_path = os.path.splitext(args.out)[0] + ".json"
    if os.path.exists(raw_path):
        with open(raw_path) as handle:
            earlier = json.load(handle)
        results = [r for r in earlier["skins"] if r["skin"] not in args.skins] + results
        versus = [r for r in earlier["ridge_vs_sklearn"] if r["skin"] not in args.skins] + versus
        order = {skin: index for index, skin in enumerate(PAPER)}
        results.sort(key=lambda r: order[r["skin"]])
        versus.sort(key=lambda r: order[r["skin"]])
    with open(raw_path, "w") as handle:
        json.dump({"skins": results, "ridge_vs_sklearn": versus}, handle, indent=1)
    lines = ["# raw, rocket and ridge on the simulated skins", "",
             "Written by `bench/compare/rocket.py` (see its docstring for the commands); one run on",
             "this machine, one thread per command. Protocol: leave one subject out (5 subjects,",
             "`tactile simulate --skin S` defaults). Feature seconds: the whole `tactile features` run",
             "(simulated recordings read, preprocessed, every segment extracted, CSV written); evaluate",
             "seconds: fit + predict summed over the folds, as `tactile evaluate` reports them.", "",
             "| skin | pipeline | classifier | accuracy % | feature s | evaluate s |", "|---|---|---|---|---|---|"]
    for row in results:
        if "failed" in row:
            lines.append(f"| {row['skin']} | {row['pipeline']} | {row['classifier']} | fails: {row['failed']} | | |")
            continue
        lines.append(f"| {row['skin']} | {row['pipeline']} | {row['classifier']} | {100 * row['accuracy']:.2f} | "
                     f"{row['feature_seconds']:.1f} | {row['evaluate_seconds']:.2f} |")
    lines += ["", "## ridge against scikit-learn's RidgeClassifierCV on the same rocket table", "",
              "Same 5 stratified folds (seed 1) on both sides; columns z-scored on the training fold with",
              "the sample deviation; alphas logspace(-3, 3, 10), leave-one-out (GCV) choice on both.", "",
              "| skin | rows x columns | ours % | scikit-learn % | ours s | scikit-learn s | time ratio (ours / sklearn) |",
              "|---|---|---|---|---|---|---|"]
    for row in versus:
        lines.append(f"| {row['skin']} | {row['rows']} x {row['columns']} | {100 * row['ours']:.2f} | "
                     f"{100 * row['sklearn']:.2f} | {row['ours_seconds']:.2f} | {row['sklearn_seconds']:.2f} | "
                     f"{row['ours_seconds'] / row['sklearn_seconds']:.2f} |")
    with open(args.out, "w") as handle:
        handle.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
