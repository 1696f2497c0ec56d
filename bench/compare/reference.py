"""The reference side of compare.py: for each of our classifier names, the scikit-learn model
(and Weka scheme) with the same algorithm and settings, plus the Weka runner and the table."""
import os
import subprocess
import time
from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np
from scipy.special import logsumexp
from sklearn.base import BaseEstimator, ClassifierMixin, TransformerMixin
from sklearn.discriminant_analysis import QuadraticDiscriminantAnalysis
from sklearn.ensemble import BaggingClassifier, GradientBoostingClassifier, RandomForestClassifier
from sklearn.mixture import GaussianMixture
from sklearn.naive_bayes import GaussianNB
from sklearn.neighbors import KNeighborsClassifier
from sklearn.pipeline import make_pipeline
from sklearn.svm import SVC
from sklearn.tree import DecisionTreeClassifier

try:  # Debian's python3-xgboost: the same library as our boosted-trees
    from xgboost import XGBClassifier
except ImportError:
    XGBClassifier = None


class SampleStandardizer(BaseEstimator, TransformerMixin):
    """z-scores with the sample deviation (n - 1), as ours and MATLAB do; StandardScaler
    divides by n. A constant column keeps scale 1 (as ours does)."""

    def fit(self, x, y=None):
        self.mean_ = x.mean(axis=0)
        deviation = x.std(axis=0, ddof=1) if len(x) > 1 else np.ones(x.shape[1])
        tiny = deviation <= 1e-12 * np.maximum(1.0, np.abs(self.mean_))
        self.scale_ = np.where(tiny, 1.0, deviation)
        return self

    def transform(self, x):
        return (x - self.mean_) / self.scale_


def auto_kernel_scale(positive, negative, rng):
    """MATLAB's KernelScale 'auto' heuristic for one binary learner (issue 5's summary):
    median distance from up to 100 positive points to their nearest of up to 100 negative
    points, times sqrt(sampled fraction)^(1/P). Drawn with numpy's generator, not ours."""
    drawn_positive = positive[rng.permutation(len(positive))[:100]]
    drawn_negative = negative[rng.permutation(len(negative))[:100]]
    distances = np.sqrt(((drawn_positive[:, None, :] - drawn_negative[None, :, :]) ** 2).sum(-1))
    fraction = len(drawn_negative) / len(negative) * len(drawn_positive) / len(positive)
    scale = np.median(distances.min(axis=1)) * np.sqrt(fraction) ** (1.0 / positive.shape[1])
    return scale if np.isfinite(scale) and scale > 0 else 1.0


class PairwiseAutoScaleSvm(BaseEstimator, ClassifierMixin):
    """One-vs-one polynomial SVMs (sklearn SVC = libsvm) with a kernel scale per pair, which
    SVC's single gamma cannot express; votes, ties to the lower class like libsvm."""

    def __init__(self, degree=2, seed=1):
        self.degree = degree
        self.seed = seed

    def fit(self, x, y):
        rng = np.random.default_rng(self.seed)
        self.classes_ = np.unique(y)
        self.learners_ = []
        for a in range(len(self.classes_)):
            for b in range(a + 1, len(self.classes_)):
                positive, negative = x[y == self.classes_[a]], x[y == self.classes_[b]]
                scale = auto_kernel_scale(positive, negative, rng)
                svm = SVC(kernel="poly", degree=self.degree, gamma=1.0 / scale**2, coef0=1.0,
                          C=1.0, tol=1e-3)
                svm.fit(np.vstack([positive, negative]),
                        np.r_[np.ones(len(positive)), -np.ones(len(negative))])
                self.learners_.append((a, b, svm))
        return self

    def predict(self, x):
        votes = np.zeros((len(x), len(self.classes_)))
        for a, b, svm in self.learners_:
            positive = svm.decision_function(x) > 0
            votes[positive, a] += 1
            votes[~positive, b] += 1
        return self.classes_[votes.argmax(axis=1)]


def silverman_width(values):
    """Ours: MAD/0.6745 * (4/(3n))^(1/5), falling back to the sample deviation."""
    n = len(values)
    robust = np.median(np.abs(values - np.median(values))) / 0.6745
    if robust <= 0 and n > 1:
        robust = values.std(ddof=1)
    return robust * (4.0 / (3.0 * n)) ** 0.2


class KernelNaiveBayes(BaseEstimator, ClassifierMixin):
    """scikit-learn has no kernel naive Bayes: a normal-kernel density per class and feature
    (the same as sklearn.neighbors.KernelDensity with one width per feature), empirical priors."""

    def fit(self, x, y):
        self.classes_ = np.unique(y)
        global_width = np.array([silverman_width(x[:, j]) for j in range(x.shape[1])])
        global_width[~(global_width > 0)] = 1.0
        self.samples_, self.widths_, self.log_priors_ = [], [], []
        for label in self.classes_:
            members = x[y == label]
            widths = np.array([silverman_width(members[:, j]) for j in range(x.shape[1])])
            widths = np.where(widths > 0, widths, global_width)
            self.samples_.append(members)
            self.widths_.append(widths)
            self.log_priors_.append(np.log(len(members) / len(y)))
        return self

    def predict(self, x):
        scores = np.zeros((len(x), len(self.classes_)))
        for k, (members, widths) in enumerate(zip(self.samples_, self.widths_)):
            z = (x[:, None, :] - members[None, :, :]) / widths
            per_feature = logsumexp(-0.5 * z**2, axis=1) - np.log(len(members)) \
                - 0.5 * np.log(2 * np.pi) - np.log(widths)
            scores[:, k] = per_feature.sum(axis=1) + self.log_priors_[k]
        return self.classes_[scores.argmax(axis=1)]


class ClusterClassifier(BaseEstimator, ClassifierMixin):
    """Classes-to-clusters as our `em` does it: a diagonal Gaussian mixture with as many
    components as classes on standardised data, each cluster labelled with its majority
    training class (lowest class on ties); a cluster that won no training row answers
    nothing (counted wrong)."""

    def __init__(self, seed=1):
        self.seed = seed

    def fit(self, x, y):
        self.classes_ = np.unique(y)
        self.mixture_ = GaussianMixture(n_components=len(self.classes_), covariance_type="diag",
                                        n_init=10, max_iter=100, tol=1e-6, reg_covar=1e-6,
                                        init_params="k-means++", random_state=self.seed)
        clusters = self.mixture_.fit_predict(x)
        self.labels_ = np.array([None] * len(self.classes_), dtype=object)
        for cluster in range(len(self.classes_)):
            members = y[clusters == cluster]
            if len(members):
                counts = [(members == label).sum() for label in self.classes_]
                self.labels_[cluster] = self.classes_[int(np.argmax(counts))]
        return self

    def predict(self, x):
        return self.labels_[self.mixture_.predict(x)]


def inverse_square(distances):
    """Weighted KNN's 1/d^2; an exact match takes the whole vote (ours does the same)."""
    with np.errstate(divide="ignore"):
        weights = 1.0 / distances**2
    exact = np.isinf(weights)
    rows = exact.any(axis=1)
    weights[rows] = exact[rows].astype(float)
    return weights


@dataclass
class Pair:
    name: str  # row label
    ours: str  # our classifier specification
    make: Callable  # (seed, feature_count) -> unfitted sklearn estimator
    describe: str
    weka: Optional[str] = None  # Weka scheme and options, on standardised fold files
    seeds: int = 1  # random restarts differ between tools: average over seeds 1..seeds


def standardised(model):
    return make_pipeline(SampleStandardizer(), model)


def svc(kernel, options):
    return lambda seed, p: standardised(SVC(kernel=kernel, C=1.0, tol=1e-3, **options(p)))


def boosted_trees_reference(seed):
    """XGBoost's own defaults as ours runs them (both cores, hist); without python3-xgboost,
    scikit-learn's GradientBoostingClassifier for information (another algorithm)."""
    if XGBClassifier is not None:
        return XGBClassifier(n_estimators=100, max_depth=6, learning_rate=0.3,
                             tree_method="hist", objective="multi:softprob", n_jobs=2,
                             random_state=seed, verbosity=0)
    return GradientBoostingClassifier(random_state=seed)


class LabelEncoded(BaseEstimator, ClassifierMixin):
    """XGBClassifier wants classes 0..K-1; the tables have names."""

    def __init__(self, model):
        self.model = model

    def fit(self, x, y):
        self.classes_, codes = np.unique(y, return_inverse=True)
        self.model.fit(x, codes)
        return self

    def predict(self, x):
        return self.classes_[np.asarray(self.model.predict(x), dtype=int)]


def tree_ensemble_pairs():
    """Random models, so the mean over 5 seeds is compared. Both sides fit on both cores."""
    return [
        Pair("random-forest", "random-forest",
             lambda seed, p: RandomForestClassifier(n_estimators=100, random_state=seed,
                                                    n_jobs=2),
             "RandomForest(100 trees, sqrt)", seeds=5),
        Pair("bagged-trees", "bagged-trees",
             lambda seed, p: BaggingClassifier(DecisionTreeClassifier(), n_estimators=30,
                                               random_state=seed, n_jobs=2),
             "Bagging(DecisionTree(), 30)", seeds=5),
        Pair("boosted-trees", "boosted-trees",
             lambda seed, p: LabelEncoded(boosted_trees_reference(seed)),
             "XGBClassifier(100, depth 6, eta 0.3, hist)" if XGBClassifier is not None
             else "GradientBoosting() (no python3-xgboost)", seeds=5),
    ]


def pairs():
    euclidean_unscaled = ('-A "weka.core.neighboursearch.LinearNNSearch -A '
                          '\\"weka.core.EuclideanDistance -D -R first-last\\""')
    return [
        Pair("linear-svm", "linear-svm", svc("linear", lambda p: {}),
             "SVC(linear, C=1)", "weka.classifiers.functions.SMO -C 1 -N 2 -L 0.001 "
             "-K \"weka.classifiers.functions.supportVector.PolyKernel -E 1.0\""),
        Pair("quadratic-svm (scale sqrtP)", "quadratic-svm:scale=sqrtP",
             svc("poly", lambda p: {"degree": 2, "gamma": 1.0 / p, "coef0": 1.0}),
             "SVC(poly 2, gamma=1/P, coef0=1)"),
        Pair("quadratic-svm (auto)", "quadratic-svm",
             lambda seed, p: standardised(PairwiseAutoScaleSvm(2, seed)),
             "SVC(poly 2) per pair, auto scale"),
        Pair("cubic-svm (scale sqrtP)", "cubic-svm:scale=sqrtP",
             svc("poly", lambda p: {"degree": 3, "gamma": 1.0 / p, "coef0": 1.0}),
             "SVC(poly 3, gamma=1/P, coef0=1)"),
        Pair("cubic-svm (auto)", "cubic-svm",
             lambda seed, p: standardised(PairwiseAutoScaleSvm(3, seed)),
             "SVC(poly 3) per pair, auto scale"),
        Pair("fine-gaussian-svm", "fine-gaussian-svm",
             svc("rbf", lambda p: {"gamma": 16.0 / p}), "SVC(rbf, gamma=16/P)"),
        Pair("medium-gaussian-svm", "medium-gaussian-svm",
             svc("rbf", lambda p: {"gamma": 1.0 / p}), "SVC(rbf, gamma=1/P)"),
        Pair("coarse-gaussian-svm", "coarse-gaussian-svm",
             svc("rbf", lambda p: {"gamma": 1.0 / (16.0 * p)}), "SVC(rbf, gamma=1/(16P))"),
        Pair("knn (k=1)", "knn",
             lambda seed, p: KNeighborsClassifier(1, algorithm="brute"),
             "KNeighbors(1), raw features", None),
        Pair("knn (k=10, standardised)", "knn:k=10,standardize=true",
             lambda seed, p: standardised(KNeighborsClassifier(10, algorithm="brute")),
             "KNeighbors(10)", "weka.classifiers.lazy.IBk -K 10 " + euclidean_unscaled),
        Pair("cosine-knn", "cosine-knn",
             lambda seed, p: standardised(
                 KNeighborsClassifier(10, metric="cosine", algorithm="brute")),
             "KNeighbors(10, cosine)"),
        Pair("weighted-knn", "weighted-knn",
             lambda seed, p: standardised(
                 KNeighborsClassifier(10, weights=inverse_square, algorithm="brute")),
             "KNeighbors(10, 1/d^2)"),
        Pair("tree", "tree",
             lambda seed, p: DecisionTreeClassifier(
                 criterion="gini", max_leaf_nodes=101, min_samples_split=10, random_state=seed),
             "DecisionTree(gini, 101 leaves)"),
        Pair("medium-tree", "medium-tree",
             lambda seed, p: DecisionTreeClassifier(
                 criterion="gini", max_leaf_nodes=21, min_samples_split=10, random_state=seed),
             "DecisionTree(gini, 21 leaves)"),
        Pair("gaussian-nb", "gaussian-nb", lambda seed, p: GaussianNB(var_smoothing=1e-9),
             "GaussianNB", "weka.classifiers.bayes.NaiveBayes"),
        Pair("kernel-nb", "kernel-nb", lambda seed, p: KernelNaiveBayes(),
             "own KDE naive Bayes (sklearn has none)", "weka.classifiers.bayes.NaiveBayes -K"),
        Pair("qda", "qda",
             lambda seed, p: standardised(QuadraticDiscriminantAnalysis(reg_param=1e-6)),
             "QDA(reg_param=1e-6) on z-scores"),
        Pair("em (classes to clusters)", "em",
             lambda seed, p: standardised(ClusterClassifier(seed)),
             "GaussianMixture(diag, K=classes)+majority", seeds=5),
    ] + tree_ensemble_pairs()


#---- Weka --------------------------------------------------------------------------------------

def write_arff(path, x, labels, classes):
    with open(path, "w") as handle:
        handle.write("@relation fold\n")
        for j in range(x.shape[1]):
            handle.write(f"@attribute f{j} numeric\n")
        handle.write("@attribute class {" + ",".join(classes) + "}\n@data\n")
        for row, label in zip(x, labels):
            handle.write(",".join(repr(float(v)) for v in row) + "," + label + "\n")


def write_weka_folds(x, labels, folds, scratch, dataset):
    """Per fold a train and a test ARFF, standardised with the training fold's mean and
    sample deviation, so Weka's own normalisation can be switched off."""
    classes = [str(c) for c in np.unique(labels)]
    files = []
    for fold in np.unique(folds):
        test = folds == fold
        scaler = SampleStandardizer().fit(x[~test])
        train_path = os.path.join(scratch, f"{dataset}-{fold}-train.arff")
        test_path = os.path.join(scratch, f"{dataset}-{fold}-test.arff")
        write_arff(train_path, scaler.transform(x[~test]), labels[~test], classes)
        write_arff(test_path, scaler.transform(x[test]), labels[test], classes)
        files.append((train_path, test_path, int(test.sum())))
    return files


def run_weka(jar, scheme, files):
    """Accuracy over the folds and the summed wall time of the JVM runs (start-up included,
    so the Weka time is an upper bound)."""
    correct, total, seconds = 0.0, 0, 0.0
    for train, test, count in files:
        command = f"java -cp {jar} {scheme} -t {train} -T {test} -o -v"
        start = time.perf_counter()
        done = subprocess.run(command, shell=True, capture_output=True, text=True)
        seconds += time.perf_counter() - start
        if done.returncode != 0:
            raise RuntimeError(f"{command}: {done.stderr.strip()[:400]}")
        section = done.stdout.split("=== Error on test data ===")[-1]
        for line in section.splitlines():
            if line.startswith("Correctly Classified Instances"):
                correct += float(line.split()[3])
                break
        else:
            raise RuntimeError(f"{command}: no accuracy in Weka's output")
        total += count
    return correct / total, seconds


#---- Table -------------------------------------------------------------------------------------

def write_table(rows, args, out):
    lines = ["# Our classifiers against scikit-learn and Weka", "",
             f"Stratified {args.folds}-fold cross-validation, the same folds on every side "
             f"(scikit-learn StratifiedKFold, shuffle, random_state={args.seed}; ours through "
             "`--protocol loso` on a fold column). Accuracy in percent; difference = ours "
             "minus scikit-learn in points; time ratio = our fit+predict seconds summed over "
             "the folds (`seconds` of `tactile evaluate --json`, one thread) / scikit-learn's "
             "(same measure, same run, same machine). Weka: per-fold JVM runs, so its time "
             "includes start-up and is not compared.", ""]

    def line(r):
        difference = 100.0 * (r["ours"] - r["sklearn"])
        flag = " **" if abs(difference) > 1.0 else ""
        weka = f"{100 * r['weka']:.2f}" if "weka" in r else "-"
        ratio = r["ours_seconds"] / r["sklearn_seconds"] if r["sklearn_seconds"] > 0 else 0
        name = r["classifier"] + (f" (mean of {r['seeds']} seeds)" if r["seeds"] > 1 else "")
        return (f"| {name} | {r['reference']} | {100 * r['ours']:.2f} | "
                f"{100 * r['sklearn']:.2f} | {difference:+.2f}{flag} | {weka} | "
                f"{ratio:.2f} ({r['ours_seconds']:.3f} s / {r['sklearn_seconds']:.3f} s) |")

    write_dataset_tables(out, lines, rows,
                         ["| classifier | reference | ours % | sklearn % | diff (pts) | Weka % | "
                          "time ours/sklearn |", "|---|---|---:|---:|---:|---:|---:|"], line)


def write_dataset_tables(out, lines, rows, header, line):
    """The page `lines` begin, then per dataset (in the order rows first name it) a section with
    its size and a table: the `header` lines, then `line(row)` for each of its rows. Written
    to a temporary file beside `out`, then renamed over it."""
    datasets = []
    for row in rows:
        if row["dataset"] not in datasets:
            datasets.append(row["dataset"])
    for dataset in datasets:
        subset = [r for r in rows if r["dataset"] == dataset]
        first = subset[0]
        lines += [f"## {dataset}: {first['rows']} rows, {first['features']} features, "
                  f"{first['classes']} classes", ""] + header
        lines += [line(r) for r in subset] + [""]
    temporary = out + ".tmp"
    with open(temporary, "w") as handle:
        handle.write("\n".join(lines))
    os.replace(temporary, out)
