#!/usr/bin/python3
"""The photo-setup plate rendered with a model and with its RGL export through `measured`, one row per view: the two
renders cropped to the plate (where they differ) and their difference (sum over R, G, B of the 8-bit sRGB values,
times 4), with labels (scripts/measured-vs-model).

usage: measured_vs_model.py OUTPUT.png TITLE LABEL=MODEL.png,MEASURED.png [LABEL=MODEL.png,MEASURED.png ...]
"""
import sys

from plotting import run, save, wrap  # this folder: atomic writes, one-line failures
from sheet_compare import difference_box
import matplotlib.image as mpimg
import matplotlib.pyplot as plt
import numpy as np


def main(argv):
    if len(argv) < 4:
        raise SystemExit(__doc__)
    output, title, rows = argv[1], argv[2], [item.split("=", 1) for item in argv[3:]]
    fig, axes = plt.subplots(len(rows), 3, figsize=(10, 2.6 * len(rows)), squeeze=False)
    for row, (label, files) in zip(axes, rows):
        model, measured = (mpimg.imread(f)[..., :3] for f in files.split(","))
        box = difference_box([model, measured]) or (0, model.shape[0], 0, model.shape[1])
        crop = [image[box[0]:box[1], box[2]:box[3]] for image in (model, measured)]
        difference = np.clip(4 * np.abs(crop[0] - crop[1]).sum(axis=2), 0, 1)
        for ax, image, caption in zip(row, crop + [difference], ["model", "exported file (measured)", "|difference| x 4"]):
            ax.imshow(image, cmap="magma" if image.ndim == 2 else None, vmin=0, vmax=1)
            ax.set_title(f"{label}: {caption}", fontsize=9)
            ax.set_xticks([]), ax.set_yticks([])
    fig.suptitle(wrap(title, 10, 11), fontsize=11)
    fig.tight_layout()
    save(fig, output, dpi=90)


if __name__ == "__main__":
    run(main, sys.argv)
