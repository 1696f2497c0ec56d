#!/usr/bin/python3
"""Is a learned model on the frames what people's grid touches need (issue 42, part 2)? A small
convolutional network over each labelled span's pressure images, leave one recording out, on the
same rows as bench/compare/grids.py (run that first: it imports the recordings and writes the
tables this reads).

Each span: every taxel minus its recording's median, clipped at zero, scaled by the grid's full
range (255), resampled to T frames; the frames are the network's input channels, plus one plane
holding the span's duration. Three networks (PyTorch, CPU, seed fixed): two convolutions with
global pooling, with and without augmentation (flips and shifts of the grid), on the
development set; the first on the simulated grids. A peer experiment,
never a dependency: /usr/bin/python3 with python3-torch, python3-h5py.

    /usr/bin/python3 bench/compare/grids_cnn.py --work /tmp/grids --out bench/compare/GRIDS_CNN.md
"""
import argparse
import datetime
import os

import numpy as np
import torch
from torch import nn

from grids import read_table, recording_frames

VARIANTS = [  # name, frames T, channels, pooling, augment
    ("8 frames, 16/32 channels, average pool", 8, (16, 32), "average", False),
    ("4 frames, 8/16 channels, max pool, flips and shifts", 4, (8, 16), "max", True),
    ("8 frames, 8/16 channels, max pool, flips and shifts", 8, (8, 16), "max", True),
]


def span_images(folder, table, frames, full_range=255.0):
    _, labels, recordings, spans, _ = read_table(table)
    cache, images = {}, []
    for recording, (t0, t1) in zip(recordings, spans):
        if recording not in cache:
            samples, rate, start, side = recording_frames(os.path.join(folder, recording + ".h5"))
            cache[recording] = (samples, rate, start, side, np.median(samples, axis=0))
        samples, rate, start, side, rest = cache[recording]
        first = max(0, int(round((t0 - start) * rate)))
        last = min(len(samples), max(first + 1, int(round((t1 - start) * rate))))
        span = np.clip(samples[first:last] - rest, 0.0, None) / full_range
        span = span.reshape(len(span), -1, side)
        position = np.linspace(0, len(span) - 1, frames)
        low = np.floor(position).astype(int)
        high = np.minimum(low + 1, len(span) - 1)
        weight = (position - low)[:, None, None]
        image = span[low] * (1 - weight) + span[high] * weight
        duration = np.full((1,) + image.shape[1:], (last - first) / rate / 5.0)
        images.append(np.concatenate([image, duration]))
    return (torch.tensor(np.array(images), dtype=torch.float32), labels, recordings)


def network(inputs, channels, pooling, classes):
    pool = nn.AdaptiveAvgPool2d(1) if pooling == "average" else nn.AdaptiveMaxPool2d(1)
    return nn.Sequential(nn.Conv2d(inputs, channels[0], 3, padding=1), nn.ReLU(), nn.MaxPool2d(2),
                         nn.Conv2d(channels[0], channels[1], 3, padding=1), nn.ReLU(), pool,
                         nn.Flatten(), nn.Dropout(0.3), nn.Linear(channels[1], classes))


def accuracy(images, labels, recordings, channels, pooling, augment, seed, epochs=100):
    classes = sorted(set(labels))
    target = torch.tensor([classes.index(label) for label in labels])
    correct = 0
    for recording in sorted(set(recordings)):
        torch.manual_seed(seed)
        test = torch.tensor(recordings == recording)
        model = network(images.shape[1], channels, pooling, len(classes))
        optimiser = torch.optim.Adam(model.parameters(), 1e-3, weight_decay=1e-4)
        train_x, train_y = images[~test], target[~test]
        for _ in range(epochs):
            model.train()
            order = torch.randperm(len(train_x))
            for begin in range(0, len(train_x), 16):
                batch = order[begin:begin + 16]
                x = train_x[batch]
                if augment:
                    if torch.rand(1) < 0.5:
                        x = x.flip(3)
                    if torch.rand(1) < 0.5:
                        x = x.flip(2)
                    x = torch.roll(x, (int(torch.randint(-3, 4, (1,))),
                                       int(torch.randint(-4, 5, (1,)))), (2, 3))
                optimiser.zero_grad()
                nn.functional.cross_entropy(model(x), train_y[batch]).backward()
                optimiser.step()
        model.eval()
        with torch.no_grad():
            correct += int((model(images[test]).argmax(1) == target[test]).sum())
    return correct / len(labels)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--work", default="/tmp/grids")
    parser.add_argument("--out", default="bench/compare/GRIDS_CNN.md")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    torch.set_num_threads(2)
    lines = []
    for name, folder in (("inflatable 19 x 27 (dev)", "dev"), ("simulated grid:16x16", "grid-16x16"),
                         ("simulated grid:19x27", "grid-19x27")):
        path = os.path.join(args.work, folder)
        # The simulated grids (400 touches) take ten minutes a network: the first one only.
        for variant, frames, channels, pooling, augment in (VARIANTS if folder == "dev" else
                                                             VARIANTS[:1]):
            images, labels, recordings = span_images(path, os.path.join(path, "grid.csv"),
                                                     frames)
            score = accuracy(images, labels, recordings, channels, pooling, augment, args.seed)
            lines.append(f"| {name} | {variant} | {len(labels)} | {100 * score:.2f} % |")
            print(lines[-1], flush=True)
    with open(args.out, "w") as handle:
        handle.write(
            "# Gestures on grids: a small CNN over the frames (issue 42, part 2)\n\n"
            f"Made by `bench/compare/grids_cnn.py` (seed {args.seed}) on "
            f"{datetime.date.today().isoformat()} with PyTorch {torch.__version__} on the CPU; "
            "leave one recording out, the rows of bench/compare/GRIDS.md.\n\n"
            "| set | network | touches | accuracy |\n|---|---|---|---|\n")
        handle.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
