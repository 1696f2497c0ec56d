#!/usr/bin/python3
"""The scikit-learn side of parity.py, as one whole process (timed from start to exit, like
`tactile evaluate`): read the CSV, cross-validate one classifier on the folds of its `fold`
column (PredefinedSplit), print {"accuracy": ..., "plain": ...} as JSON.

    /usr/bin/python3 bench/compare/parity_sklearn.py --features T.csv --row medium-gaussian-svm

Only the modules a row needs are imported. Standardisation is inside the fold with the sample
deviation (n - 1), as ours. `plain` is scikit-learn's own answer; `accuracy` the reference
the parity check uses: the same except for the k-NN rows with equal votes, where it applies
our tie rule (the nearest neighbour among the tied classes) to scikit-learn's neighbours.
"""
import argparse
import json

import numpy as np


def read_table(path):
    with open(path) as handle:
        header = handle.readline().rstrip("\n").split(",")
    label_column, fold_column = header.index("class"), header.index("fold")
    x = np.loadtxt(path, delimiter=",", skiprows=1, usecols=range(label_column), ndmin=2)
    text = np.loadtxt(path, delimiter=",", skiprows=1, usecols=(label_column, fold_column),
                      dtype=str, ndmin=2)
    return x, text[:, 0], text[:, 1].astype(int)


def standardise(train, test):
    mean = train.mean(axis=0)
    deviation = train.std(axis=0, ddof=1)
    deviation = np.where(deviation <= 1e-12 * np.maximum(1.0, np.abs(mean)), 1.0, deviation)
    return (train - mean) / deviation, (test - mean) / deviation


def nearest_tied(neighbour_labels, weights, classes):
    """Our k-NN rule: the most votes; between tied classes, the nearest neighbour's."""
    predicted = np.empty(len(neighbour_labels), dtype=classes.dtype)
    for row, (labels, weight) in enumerate(zip(neighbour_labels, weights)):
        votes = {}
        for label, w in zip(labels, weight):
            votes[label] = votes.get(label, 0.0) + w
        best = max(votes.values())
        predicted[row] = next(label for label in labels if votes[label] == best)
    return predicted


def inverse_square(distances):
    with np.errstate(divide="ignore"):
        weights = 1.0 / distances**2
    exact = np.isinf(weights)
    rows = exact.any(axis=1)
    weights[rows] = exact[rows].astype(float)
    return weights


SVC_ROWS = {  # name -> SVC options given P
    "linear-svm": lambda p: {"kernel": "linear"},
    "quadratic-svm (scale sqrtP)": lambda p: {"kernel": "poly", "degree": 2, "gamma": 1.0 / p,
                                              "coef0": 1.0},
    "cubic-svm (scale sqrtP)": lambda p: {"kernel": "poly", "degree": 3, "gamma": 1.0 / p,
                                          "coef0": 1.0},
    "fine-gaussian-svm": lambda p: {"kernel": "rbf", "gamma": 16.0 / p},
    "medium-gaussian-svm": lambda p: {"kernel": "rbf", "gamma": 1.0 / p},
    "coarse-gaussian-svm": lambda p: {"kernel": "rbf", "gamma": 1.0 / (16.0 * p)},
    "rbf C=100 gamma=1/P": lambda p: {"kernel": "rbf", "gamma": 1.0 / p, "C": 100.0},
    "medium-gaussian-svm, votes only": lambda p: {"kernel": "rbf", "gamma": 1.0 / p},
    "medium-gaussian-svm, probabilities": lambda p: {"kernel": "rbf", "gamma": 1.0 / p,
                                                     "probability": True, "random_state": 1},
    "balanced rbf": lambda p: {"kernel": "rbf", "gamma": 1.0 / p, "class_weight": "balanced"},
}
KNN_ROWS = {  # name -> (k, metric, weights, standardised)
    "knn (k=1)": (1, "euclidean", "uniform", False),
    "knn (k=10, standardised)": (10, "euclidean", "uniform", True),
    "cosine-knn": (10, "cosine", "uniform", True),
    "weighted-knn": (10, "euclidean", "inverse_square", True),
}
TREE_ROWS = {"tree": 100, "medium-tree": 20}


def fold_predictions(row, seed, x_train, y_train, x_test):
    """(reference prediction, scikit-learn's own prediction) for one fold."""
    p = x_train.shape[1]
    if row in SVC_ROWS:
        from sklearn.svm import SVC
        options = {"C": 1.0, "tol": 1e-3, "cache_size": 200, **SVC_ROWS[row](p)}
        z_train, z_test = standardise(x_train, x_test)
        predicted = SVC(**options).fit(z_train, y_train).predict(z_test)
        return predicted, predicted
    if row in ("quadratic-svm (auto)", "cubic-svm (auto)"):
        import reference
        z_train, z_test = standardise(x_train, x_test)
        model = reference.PairwiseAutoScaleSvm(2 if row.startswith("quadratic") else 3, seed)
        predicted = model.fit(z_train, y_train).predict(z_test)
        return predicted, predicted
    if row in KNN_ROWS:
        from sklearn.neighbors import KNeighborsClassifier
        k, metric, weights, standardised = KNN_ROWS[row]
        if standardised:
            x_train, x_test = standardise(x_train, x_test)
        model = KNeighborsClassifier(k, metric=metric, algorithm="brute",
                                     weights=inverse_square if weights == "inverse_square"
                                     else weights).fit(x_train, y_train)
        plain = model.predict(x_test)
        distances, indices = model.kneighbors(x_test)
        votes = inverse_square(distances) if weights == "inverse_square" else \
            np.ones_like(distances)
        return nearest_tied(y_train[indices], votes, model.classes_), plain
    if row == "subspace-knn":
        from sklearn.ensemble import BaggingClassifier
        from sklearn.neighbors import KNeighborsClassifier
        z_train, z_test = standardise(x_train, x_test)
        model = BaggingClassifier(KNeighborsClassifier(1, algorithm="brute"), n_estimators=30,
                                  max_samples=1.0, bootstrap=False, max_features=0.5,
                                  bootstrap_features=False, random_state=seed)
        predicted = model.fit(z_train, y_train).predict(z_test)
        return predicted, predicted
    if row in TREE_ROWS:
        from sklearn.tree import DecisionTreeClassifier
        plain = DecisionTreeClassifier(criterion="gini", max_leaf_nodes=TREE_ROWS[row] + 1,
                                       min_samples_split=10, random_state=seed)
        plain_predicted = plain.fit(x_train, y_train).predict(x_test)
        full = DecisionTreeClassifier(criterion="gini", min_samples_split=10,
                                      random_state=seed).fit(x_train, y_train)
        return layer_wise(full, TREE_ROWS[row], x_test), plain_predicted
    raise SystemExit(f"no scikit-learn row named '{row}'")


def layer_wise(full, max_splits, x_test):
    """Our (fitctree's) cap on splits applied to scikit-learn's fully grown CART: layer by
    layer, the splittable nodes with the largest gain (node share x Gini decrease) first, ties
    left to right, until max_splits branch nodes; the rest become leaves. scikit-learn's own
    max_leaf_nodes grows best-first over the whole tree instead."""
    tree = full.tree_
    total = tree.weighted_n_node_samples[0]

    def gain(node):
        left, right = tree.children_left[node], tree.children_right[node]
        n = tree.weighted_n_node_samples
        decrease = tree.impurity[node] - (n[left] * tree.impurity[left] +
                                          n[right] * tree.impurity[right]) / n[node]
        return n[node] / total * decrease

    branch = set()
    layer, left_over = [0], max_splits
    while layer and left_over > 0:
        candidates = [(position, node) for position, node in enumerate(layer)
                      if tree.children_left[node] != -1 and gain(node) > 1e-12]
        candidates.sort(key=lambda c: -gain(c[1]))  # stable: ties stay left to right
        candidates = sorted(candidates[:left_over])
        left_over -= len(candidates)
        branch.update(node for _, node in candidates)
        layer = [child for _, node in candidates
                 for child in (tree.children_left[node], tree.children_right[node])]
    x32 = x_test.astype(np.float32)
    predicted = np.empty(len(x_test), dtype=full.classes_.dtype)
    for row in range(len(x_test)):
        node = 0
        while node in branch:
            node = (tree.children_left[node] if x32[row, tree.feature[node]] <= tree.threshold[node]
                    else tree.children_right[node])
        predicted[row] = full.classes_[int(np.argmax(tree.value[node][0]))]
    return predicted



def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--features", required=True)
    parser.add_argument("--row", required=True)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--seeds", type=int, default=1,
                        help="tree rows: random_state seed .. seed + seeds - 1, mean reported")
    args = parser.parse_args()
    import warnings
    warnings.filterwarnings("ignore")
    x, labels, folds = read_table(args.features)
    from sklearn.model_selection import PredefinedSplit
    # The tree rows over several random_state values (--seeds): scikit-learn's CART tries the
    # features in an order drawn from it and keeps the first of equally good splits, so its
    # accuracy is a draw; `accuracy` is then the mean over the seeds, `seeds` each one.
    seeds = list(range(args.seed, args.seed + (args.seeds if args.row in TREE_ROWS else 1)))
    accuracies, plains = [], []
    for seed in seeds:
        correct = plain_correct = 0
        for train, test in PredefinedSplit(folds).split():
            reference, plain = fold_predictions(args.row, seed, x[train], labels[train],
                                                x[test])
            correct += int(np.sum(reference == labels[test]))
            plain_correct += int(np.sum(plain == labels[test]))
        accuracies.append(correct / len(labels))
        plains.append(plain_correct / len(labels))
    print(json.dumps({"accuracy": float(np.mean(accuracies)), "plain": float(np.mean(plains)),
                      "seeds": accuracies, "plain_seeds": plains}))


if __name__ == "__main__":
    main()
