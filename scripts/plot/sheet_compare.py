#!/usr/bin/python3
"""Lays rendered PNGs out as one labelled comparison sheet (the layout of the supplemental's Figures 3-8).

usage: sheet_compare.py OUTPUT.png TITLE COLUMNS LABEL=IMAGE.png [LABEL=IMAGE.png ...]
Panels fill rows of COLUMNS from the top left; a label "-" leaves a panel empty, an image that does not exist (its
render failed) leaves it empty with its label marked "(missing)". Panels keep their own aspect.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) < 5:
        sys.exit(__doc__)
    output, title, columns = argv[1], argv[2], int(argv[3])
    panels = []
    for item in argv[4:]:
        label, _, path = item.partition("=")
        panels.append((label, path))
    rows = (len(panels) + columns - 1) // columns
    present = [p for label, p in panels if label != "-" and os.path.exists(p)]
    if not present:
        sys.exit("sheet_compare.py: none of the panel images exists")
    first = mpimg.imread(present[0])
    aspect = first.shape[0] / first.shape[1]
    width = 3.2 * columns
    fig, axes = plt.subplots(rows, columns, figsize=(width, 3.2 * aspect * rows + 0.7), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, (label, path) in zip(axes.flat, panels):
        if label == "-":
            continue
        if not os.path.exists(path):
            ax.set_title(label + " (missing)", fontsize=10, color="0.5")
            continue
        ax.imshow(mpimg.imread(path))
        ax.set_title(label, fontsize=10)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    fig.savefig(output, dpi=110)


if __name__ == "__main__":
    main(sys.argv)
