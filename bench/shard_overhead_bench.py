#!/usr/bin/python3
"""What sharding costs on one machine (issue 29): the CPU time of a corpus job run as N shards
plus their merge, against the same job in one process, and whether the results are the same
bytes.

For each corpus (simulated, one process): `tactile features` over every recording, then
`tactile evaluate --classifier all --protocol kfold:5 --no-timings` (train-all, 5-fold CV) on
that table. Each job runs once in one process and once as N shards one after another, then
`tactile merge`. CPU time is user + system of each process (getrusage of the children), so
the shards' sum is comparable with the one process whatever the thread count.

Writes bench/compare/SHARDS.md. Usage: bench/shard_overhead_bench.py [BUILD_DIR] [SHARDS]
Run it on a quiet machine: other load inflates the CPU time of spinning thread pools.
"""
import filecmp
import os
import resource
import subprocess
import sys
import tempfile
import time

BUILD = sys.argv[1] if len(sys.argv) > 1 else "build"
SHARDS = int(sys.argv[2]) if len(sys.argv) > 2 else 4
TACTILE = os.path.abspath(os.path.join(BUILD, "bin", "tactile"))
OUT = "bench/compare/SHARDS.md"
# (skin, subjects, trials, pipeline): at least 40 recordings each.
CORPORA = [("fur", 10, 4, "fur"), ("nao", 8, 5, "kaboli")]
if os.environ.get("SHARD_BENCH_QUICK"):  # a smoke run of the script itself
    CORPORA = [("fur", 2, 2, "fur")]


def cpu_of(arguments):
    """Runs `tactile ARGUMENTS`; returns (cpu seconds, wall seconds)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    subprocess.run([TACTILE] + arguments, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall


def measure(arguments, result, work, name):
    """One process, then SHARDS shards and the merge: the row of the table."""
    one = os.path.join(work, name + "-one" + os.path.splitext(result)[1])
    merged = os.path.join(work, name + "-merged" + os.path.splitext(result)[1])
    one_cpu, one_wall = cpu_of(arguments + ["--out", one])
    shard_cpu = shard_wall = 0.0
    parts = []
    for index in range(1, SHARDS + 1):
        parts.append(os.path.join(work, "%s.part-%d" % (name, index)))
        cpu, wall = cpu_of(arguments + ["--out", merged, "--shard", "%d/%d" % (index, SHARDS),
                                        "--part", parts[-1]])
        shard_cpu += cpu
        shard_wall = max(shard_wall, wall)
    merge_cpu, _ = cpu_of(["merge"] + parts + ["--out", merged])
    same = filecmp.cmp(one, merged, shallow=False)
    return {"one": one_cpu, "one_wall": one_wall, "shards": shard_cpu, "merge": merge_cpu,
            "slowest": shard_wall, "same": same, "table": one}


def main():
    rows = []
    with tempfile.TemporaryDirectory(prefix="shard-bench-") as work:
        for skin, subjects, trials, pipeline in CORPORA:
            folder = os.path.join(work, skin)
            subprocess.run([TACTILE, "simulate", "--skin", skin, "--subjects", str(subjects),
                            "--trials", str(trials), "--out", folder], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            recordings = subjects * trials
            features = measure(["features", "--pipeline", pipeline, "--labels",
                                os.path.join(folder, "labels.db")],
                               "table.csv", work, skin + "-features")
            rows.append(("%s, %d recordings" % (skin, recordings), "features --pipeline " + pipeline,
                         features))
            evaluate = measure(["evaluate", "--features", features["table"], "--classifier",
                                "all", "--protocol", "kfold:5", "--no-timings"],
                               "result.json", work, skin + "-evaluate")
            rows.append(("%s, %d recordings" % (skin, recordings),
                         "evaluate --classifier all --protocol kfold:5", evaluate))
            print(rows[-2][0], "done", file=sys.stderr)
    lines = [
        "# Sharding on one machine: CPU time of %d shards + merge against one process" % SHARDS,
        "",
        "Made by `bench/shard_overhead_bench.py` on %s (%d cores); CPU = user + system time of"
        % (time.strftime("%Y-%m-%d", time.gmtime()), os.cpu_count()),
        "each process, shards run one after another. Ratio = (shards + merge) / one process.",
        "",
        "| corpus | job | one process CPU s | %d shards CPU s | merge CPU s | ratio | same bytes |"
        % SHARDS,
        "|---|---|---:|---:|---:|---:|---|",
    ]
    for corpus, job, row in rows:
        ratio = (row["shards"] + row["merge"]) / row["one"] if row["one"] > 0 else float("nan")
        lines.append("| %s | `%s` | %.2f | %.2f | %.2f | %.3f | %s |" % (
            corpus, job, row["one"], row["shards"], row["merge"], ratio,
            "yes" if row["same"] else "NO"))
    total_one = sum(row["one"] for _, _, row in rows)
    total_sharded = sum(row["shards"] + row["merge"] for _, _, row in rows)
    lines.append("| all | | %.2f | | | %.3f | %s |" % (
        total_one, total_sharded / total_one,
        "yes" if all(row["same"] for _, _, row in rows) else "NO"))
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as out:
        out.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
