#!/usr/bin/python3
"""Lays rendered PNGs out as one labelled comparison sheet (the layout of the supplemental's Figures 3-8).

usage: sheet_compare.py OUTPUT.png TITLE COLUMNS [--crop-to-difference] LABEL=IMAGE.png [LABEL=IMAGE.png ...]
Panels fill rows of COLUMNS from the top left; a label "-" leaves a panel empty, an image that does not exist (its
render failed) leaves it empty with its label marked "(missing)". Panels keep their own aspect. A LABEL may have
several lines ("\\n"): the first is the panel's title, the others its caption; a caption line starting with "!" is
a warning, drawn in red.

--crop-to-difference crops the panels of the most common size to where they differ from each other (the sample,
when the models differ only in its material), with a margin, at their aspect; it crops nothing when they do not
differ, differ nearly everywhere, or there is one such panel.
"""
import os
import sys

from plotting import run, save  # this folder: atomic writes, one-line failures
import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def box_blur(values, radius):
    """Mean over a (2 radius + 1)^2 box, edges clamped (summed-area table)."""
    padded = np.pad(values, radius + 1, mode="edge")
    table = padded.cumsum(0).cumsum(1)
    k = 2 * radius + 1
    s = table[k:, k:] - table[:-k, k:] - table[k:, :-k] + table[:-k, :-k]
    return s[: values.shape[0], : values.shape[1]] / (k * k)


def difference_box(images):
    """(y0, y1, x0, x1) around where the images differ, or None."""
    first = images[0][..., :3].astype(np.float64)
    difference = np.zeros(first.shape[:2])
    for image in images[1:]:
        difference = np.maximum(difference, np.abs(image[..., :3] - first).sum(axis=2))
    height, width = difference.shape
    smooth = box_blur(difference, max(1, round(0.02 * max(height, width))))
    if smooth.max() <= 1e-3:
        return None
    ys, xs = np.nonzero(smooth > 0.2 * smooth.max())
    y0, y1, x0, x1 = ys.min(), ys.max() + 1, xs.min(), xs.max() + 1
    # A quarter of the box's size as margin on each side, then widened to the images' aspect.
    cy, cx = 0.5 * (y0 + y1), 0.5 * (x0 + x1)
    half_h, half_w = 0.75 * (y1 - y0), 0.75 * (x1 - x0)
    aspect = height / width
    half_h, half_w = max(half_h, half_w * aspect, 4.0), max(half_w, half_h / aspect, 4.0)
    if half_h * half_w * 4 > 0.7 * height * width:
        return None
    y0 = int(max(0, min(height - 2 * half_h, cy - half_h)))
    x0 = int(max(0, min(width - 2 * half_w, cx - half_w)))
    return y0, int(min(height, y0 + 2 * half_h)), x0, int(min(width, x0 + 2 * half_w))


def main(argv):
    if len(argv) < 5:
        sys.exit(__doc__)
    output, title, columns = argv[1], argv[2], int(argv[3])
    items = argv[4:]
    crop = bool(items) and items[0] == "--crop-to-difference"
    if crop:
        items = items[1:]
    panels = []
    for item in items:
        label, _, path = item.partition("=")
        panels.append((label, path))
    rows = (len(panels) + columns - 1) // columns
    present = [p for label, p in panels if label != "-" and os.path.exists(p)]
    if not present:
        sys.exit("sheet_compare.py: none of the panel images exists")
    images = {p: mpimg.imread(p) for p in present}
    if crop:
        shapes = [images[p].shape for p in present]
        common = max(set(shapes), key=shapes.count)
        same = [p for p in present if images[p].shape == common]
        box = difference_box([images[p] for p in same]) if len(same) > 1 else None
        if box:
            y0, y1, x0, x1 = box
            for p in same:
                images[p] = images[p][y0:y1, x0:x1]
            title += f" (cropped to where the models differ: {x1 - x0} x {y1 - y0} of {common[1]} x {common[0]} px)"
    first = images[present[0]]
    aspect = first.shape[0] / first.shape[1]
    caption_lines = max(len(label.split("\n")) for label, _ in panels)
    width = 3.2 * columns
    panel_height = 3.2 * aspect + 0.18 * max(0, caption_lines - 1)
    fig, axes = plt.subplots(rows, columns, figsize=(width, panel_height * rows + 0.7), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, (label, path) in zip(axes.flat, panels):
        if label == "-":
            continue
        lines = label.split("\n")
        if not os.path.exists(path):
            ax.set_title(lines[0] + " (missing)", fontsize=10, color="0.5")
            continue
        ax.imshow(images[path], interpolation="nearest" if crop else "antialiased")
        ax.set_title(lines[0], fontsize=10)
        for i, line in enumerate(lines[1:]):
            warning = line.startswith("!")
            ax.text(0.5, -0.03 - 0.085 * i, line[1:] if warning else line, transform=ax.transAxes, ha="center",
                    va="top", fontsize=8, color="#c00000" if warning else "0.25",
                    fontweight="bold" if warning else "normal")
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    save(fig, output, dpi=110)


if __name__ == "__main__":
    run(main, sys.argv)
