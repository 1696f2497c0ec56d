#!/usr/bin/python3
"""Issue 26's target on the simulated skins: the paper pipeline against generic, raw, rocket
and the `auto` pipeline (generic+grid+raw+rocket), leave one subject out.

Reads bench/compare/ROCKET.json (bench/compare/rocket.py: paper, generic, raw and rocket
rows) and adds, per skin, the `auto` pipeline's table evaluated with ridge, linear-svm and
random-forest and, where asked (--auto-skins), with `--classifier auto` under a time and
memory limit (auto on a wide table is slow: nao's 19,099 columns took > 7 min, and tsa's
31,625 columns grew past 18 GB before the kernel killed it). One thread per command.

    /usr/bin/python3 bench/compare/skins.py --tactile build/bin/tactile --work /tmp/rocket \\
        --out bench/compare/SKINS.md

--work must hold the simulated skins (rocket.py's work folder: WORK/SKIN/labels.db).
"""
import argparse
import json
import os
import resource
import subprocess
import time

PAPER = {"nao": "kaboli", "tsa": "tsa_event", "fur": "fur", "robovie": "robovie_xcorr", "flux": "flux"}
FIXED = ["ridge", "linear-svm", "random-forest"]


def limited(memory_bytes):
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
    return apply


def run(command, timeout=None, memory_bytes=None):
    began = time.perf_counter()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout,
                              preexec_fn=limited(memory_bytes) if memory_bytes else None)
    except subprocess.TimeoutExpired:
        return None, time.perf_counter() - began, f"stopped after {timeout} s"
    if done.returncode != 0:
        last = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else f"exit {done.returncode}"
        return None, time.perf_counter() - began, last
    return done.stdout, time.perf_counter() - began, ""


def evaluate(tactile, table, classifier, timeout=None, memory_bytes=None):
    out, seconds, failure = run([tactile, "evaluate", "--features", table, "--classifier", classifier,
                                 "--protocol", "loso", "--threads", "1", "--json"], timeout, memory_bytes)
    if out is None:
        return {"classifier": classifier, "failed": failure, "wall_seconds": seconds}
    result = json.loads(out)
    return {"classifier": classifier, "accuracy": result["accuracy"], "seconds": result["seconds"],
            "wall_seconds": seconds}


def best(rows, skin, pipeline, classifiers=None):
    found = [r for r in rows if r["skin"] == skin and r["pipeline"] == pipeline and "accuracy" in r
             and (classifiers is None or r["classifier"] in classifiers)]
    return max(found, key=lambda r: r["accuracy"]) if found else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tactile", default="build/bin/tactile")
    parser.add_argument("--work", default="/tmp/rocket")
    parser.add_argument("--rocket-json", default="bench/compare/ROCKET.json")
    parser.add_argument("--out", default="bench/compare/SKINS.md")
    parser.add_argument("--skins", nargs="*", default=list(PAPER))
    parser.add_argument("--auto-skins", nargs="*", default=list(PAPER),
                        help="skins whose auto-pipeline table is also evaluated with --classifier auto")
    parser.add_argument("--auto-timeout", type=float, default=900.0)
    parser.add_argument("--auto-memory-gb", type=float, default=6.0)
    parser.add_argument("--auto-json", nargs="*", default=[],
                        help="SKIN=FILE: `tactile evaluate --classifier auto --json` output of an earlier "
                             "run on this skin's auto-pipeline table, used instead of running it again")
    args = parser.parse_args()
    with open(args.rocket_json) as handle:
        earlier = json.load(handle)["skins"]
    results = []
    for skin in args.skins:
        table = os.path.join(args.work, f"{skin}-auto.csv")
        _, feature_seconds, failure = run([args.tactile, "features", "--pipeline", "auto", "--threads", "1",
                                           "--labels", os.path.join(args.work, skin, "labels.db"), "--out", table])
        entry = {"skin": skin, "feature_seconds": feature_seconds, "runs": []}
        if failure:
            entry["failed"] = failure
        else:
            with open(table) as handle:
                entry["columns"] = sum("/" in name for name in handle.readline().split(","))
            for classifier in FIXED:
                entry["runs"].append(evaluate(args.tactile, table, classifier))
                print(skin, entry["runs"][-1], flush=True)
            given = dict(item.split("=", 1) for item in args.auto_json)
            if skin in given:
                with open(given[skin]) as handle:
                    result = json.load(handle)
                entry["runs"].append({"classifier": "auto", "accuracy": result["accuracy"],
                                      "seconds": result["seconds"], "wall_seconds": float("nan")})
            elif skin in args.auto_skins:
                entry["runs"].append(evaluate(args.tactile, table, "auto", args.auto_timeout,
                                              int(args.auto_memory_gb * 2**30)))
                print(skin, entry["runs"][-1], flush=True)
            # auto on each pipeline's own table (rocket.py wrote them into --work).
            entry["pipeline_auto"] = {}
            for pipeline in ["generic", "raw", "rocket"]:
                own = os.path.join(args.work, f"{skin}-{pipeline}.csv")
                if skin in args.auto_skins and os.path.exists(own):
                    entry["pipeline_auto"][pipeline] = evaluate(args.tactile, own, "auto", args.auto_timeout,
                                                                int(args.auto_memory_gb * 2**30))
                    print(skin, pipeline, entry["pipeline_auto"][pipeline], flush=True)
        results.append(entry)
    raw_path = os.path.splitext(args.out)[0] + ".json"
    with open(raw_path, "w") as handle:
        json.dump({"auto_pipeline": results}, handle, indent=1)

    def cell(row):
        return f"{100 * row['accuracy']:.2f} ({row['classifier']})" if row else "-"

    lines = ["# Issue 26's target on the simulated skins", "",
             "Written by `bench/compare/skins.py` (see its docstring); paper, generic, raw and rocket rows",
             "from bench/compare/ROCKET.json (`bench/compare/rocket.py`), the `auto` pipeline",
             "(generic+grid+raw+rocket) run here. Leave one subject out, accuracy %, one thread per command.", "",
             "| skin | paper (best) | generic (best) | raw + RBF SVM | rocket + ridge | auto pipeline (best fixed classifier) "
             "| auto pipeline + `--classifier auto` | `--classifier auto` on generic / raw / rocket "
             "| best with `auto` | vs paper | best of all | vs paper | vs raw SVM |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for entry in results:
        skin = entry["skin"]
        paper = best(earlier, skin, PAPER[skin])
        generic = best(earlier, skin, "generic")
        raw_svm = best(earlier, skin, "raw", ["medium-gaussian-svm"])
        rocket = best(earlier, skin, "rocket", ["ridge"])
        fixed = [r for r in entry["runs"] if "accuracy" in r and r["classifier"] in FIXED]
        fixed_best = max(fixed, key=lambda r: r["accuracy"]) if fixed else None
        auto = next((r for r in entry["runs"] if r["classifier"] == "auto"), None)
        if "failed" in entry:
            fixed_cell, auto_cell = f"fails: {entry['failed']}", "-"
        else:
            fixed_cell = cell(fixed_best)
            if auto is None:
                auto_cell = "not run (too slow on this table)"
            elif "failed" in auto:
                auto_cell = f"fails: {auto['failed']}"
            else:
                auto_cell = f"{100 * auto['accuracy']:.2f} ({auto['seconds']:.0f} s)"
        own_auto = entry.get("pipeline_auto", {})
        own_cell = " / ".join(f"{100 * own_auto[p]['accuracy']:.2f}" if "accuracy" in own_auto.get(p, {}) else "-"
                              for p in ["generic", "raw", "rocket"])
        with_auto = [dict(r, pipeline=p) for p, r in own_auto.items() if "accuracy" in r]
        with_auto += [dict(auto, pipeline="auto")] if auto and "accuracy" in auto else []
        top_auto = max(with_auto, key=lambda r: r["accuracy"]) if with_auto else None
        auto_best_cell = f"{100 * top_auto['accuracy']:.2f} ({top_auto['pipeline']})" if top_auto else "-"
        versus_paper_auto = (f"{100 * (top_auto['accuracy'] - paper['accuracy']):+.2f}"
                             if top_auto and paper else "-")
        candidates = [r for r in [generic, raw_svm, best(earlier, skin, "raw"), rocket] if r]
        candidates += [dict(r, pipeline="auto") for r in entry["runs"] if "accuracy" in r]
        candidates += with_auto
        top = max(candidates, key=lambda r: r["accuracy"])
        top_name = f"{100 * top['accuracy']:.2f} ({top.get('pipeline', 'auto')} + {top['classifier']})"
        versus_paper = f"{100 * (top['accuracy'] - paper['accuracy']):+.2f}" if paper else "-"
        versus_raw = f"{100 * (top['accuracy'] - raw_svm['accuracy']):+.2f}" if raw_svm else "-"
        lines.append(f"| {skin} | {cell(paper)} | {cell(generic)} | {cell(raw_svm)} | {cell(rocket)} | {fixed_cell} | "
                     f"{auto_cell} | {own_cell} | {auto_best_cell} | {versus_paper_auto} | {top_name} | "
                     f"{versus_paper} | {versus_raw} |")
    lines += ["", "## The auto pipeline's runs", "",
              "| skin | columns | feature s | classifier | accuracy % | evaluate s (fit + predict) | wall s |",
              "|---|---|---|---|---|---|---|"]
    for entry in results:
        if "failed" in entry:
            lines.append(f"| {entry['skin']} | | {entry['feature_seconds']:.1f} | | fails: {entry['failed']} | | |")
            continue
        for r in entry["runs"]:
            if "accuracy" in r:
                lines.append(f"| {entry['skin']} | {entry['columns']} | {entry['feature_seconds']:.1f} | "
                             f"{r['classifier']} | {100 * r['accuracy']:.2f} | {r['seconds']:.1f} | {r['wall_seconds']:.0f} |")
            else:
                lines.append(f"| {entry['skin']} | {entry['columns']} | {entry['feature_seconds']:.1f} | "
                             f"{r['classifier']} | fails: {r['failed']} | | {r['wall_seconds']:.0f} |")
    with open(args.out, "w") as handle:
        handle.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
