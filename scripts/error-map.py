#!/usr/bin/env python3
"""Where a technique's caustic irradiance differs from the reference's, and how much.

    error-map.py REFERENCE.exr IMAGE.exr [--blocks 16] [--output error-map.png]

REFERENCE.exr: a vtkCausticsReferenceRenderer image (caustics-bench's cached ground
truth, `<build>/reference-cache/reference-<hash>.exr`, the hash in the generated table
of docs/benchmarks.md): CausticIrradiance, ReceiverMask, PixelArea.
IMAGE.exr: the technique's caustic irradiance, as `caustics-bench --images` writes it
(layer `caustic`), or a caustics-render EXR (same layer name).

Prints the relative L2 error and flux ratio on the reference's receiver pixels,
weighted by pixel area (as vtkCausticsErrorMetrics; the benchmark's figures come from
that class), how much of the squared error is missing light (image below the
reference) or extra light, and the blocks of the image that hold most of it (x, y in
pixels from the top-left corner). With --output, a PNG of the reference, the image and
their signed difference (needs matplotlib).

Reads EXR layers with `oiiotool` (Debian: openimageio-tools), which converts each one
to FITS, a format the standard library and numpy read.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np


def read_channel(path, channel, scratch):
    """One channel of an EXR as a float64 array, row 0 at the top of the image."""
    out = os.path.join(scratch, "channel.fits")
    subprocess.run(["oiiotool", path, "--ch", channel, "-d", "float", "-o", out],
                   check=True, stdout=subprocess.DEVNULL)
    raw = open(out, "rb").read()
    header, offset = {}, 0
    while True:
        card = raw[offset:offset + 80].decode("ascii")
        offset += 80
        key = card[:8].strip()
        if card[8:10] == "= ":
            header[key] = card[10:].split("/")[0].strip()
        if key == "END":
            break
    start = (offset + 2879) // 2880 * 2880
    width, height = int(header["NAXIS1"]), int(header["NAXIS2"])
    data = np.frombuffer(raw[start:start + 4 * width * height], dtype=">f4")
    # FITS stores the bottom row first.
    return data.reshape(height, width)[::-1].astype(np.float64)


def rgb(path, layer, scratch):
    return np.stack([read_channel(path, layer + "." + c, scratch) for c in "RGB"], axis=-1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("reference")
    parser.add_argument("image")
    parser.add_argument("--blocks", type=int, default=16, help="block size in pixels")
    parser.add_argument("--top", type=int, default=5, help="blocks to list")
    parser.add_argument("--output", help="PNG of reference, image and difference")
    args = parser.parse_args()
    for path in (args.reference, args.image):
        if not os.path.isfile(path):
            sys.exit("error-map: no such file: " + path)

    with tempfile.TemporaryDirectory() as scratch:
        try:
            truth = rgb(args.reference, "CausticIrradiance", scratch)
            mask = read_channel(args.reference, "ReceiverMask.Y", scratch) > 0.5
            area = read_channel(args.reference, "PixelArea.Y", scratch)
            test = rgb(args.image, "caustic", scratch)
        except FileNotFoundError:
            sys.exit("error-map: needs oiiotool (Debian package openimageio-tools)")
        except subprocess.CalledProcessError as e:
            sys.exit("error-map: oiiotool could not read a layer: " + " ".join(e.cmd[1:4]))
    if truth.shape != test.shape:
        sys.exit("error-map: the images differ in size: %s and %s" %
                 (truth.shape[:2], test.shape[:2]))

    weight = np.where(mask, area, 0.0)[..., None]
    difference = test - truth
    squared = (difference ** 2 * weight).sum(axis=-1)
    total = squared.sum()
    norm = (truth ** 2 * weight).sum()
    if not norm > 0.0:
        sys.exit("error-map: the reference has no caustic light on its receivers")
    flux = (test * weight).sum() / (truth * weight).sum()
    print("relative L2 %.4f, flux ratio %.4f, %d receiver pixels" %
          (np.sqrt(total / norm), flux, mask.sum()))
    if not total > 0.0:
        return
    missing = (np.minimum(difference, 0.0) ** 2 * weight).sum() / total
    print("squared error: %.1f %% missing light, %.1f %% extra light" %
          (100.0 * missing, 100.0 * (1.0 - missing)))

    b = args.blocks
    height, width = squared.shape
    rows, cols = (height + b - 1) // b, (width + b - 1) // b
    padded = np.zeros((rows * b, cols * b))
    padded[:height, :width] = squared
    blocks = padded.reshape(rows, b, cols, b).sum(axis=(1, 3))
    order = np.argsort(blocks.ravel())[::-1][:args.top]
    print("blocks holding the most squared error (x, y from the top-left corner):")
    for k in order:
        r, c = divmod(int(k), cols)
        print("  x %3d..%3d  y %3d..%3d  %5.1f %%" %
              (c * b, min((c + 1) * b, width) - 1, r * b, min((r + 1) * b, height) - 1,
               100.0 * blocks[r, c] / total))

    if args.output:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            sys.exit("error-map: --output needs matplotlib")
        luminance = lambda a: np.where(mask, a.mean(axis=-1), 0.0)
        top = np.percentile(luminance(truth)[mask], 99.9)
        fig, axes = plt.subplots(1, 3, figsize=(12, 4.2))
        for ax, image, title in ((axes[0], luminance(truth), "reference"),
                                 (axes[1], luminance(test), "image")):
            ax.imshow(image, vmin=0.0, vmax=top)
            ax.set_title(title + " (W/m², clipped at the 99.9th percentile)", fontsize=8)
        shown = axes[2].imshow(luminance(difference), cmap="RdBu_r", vmin=-top / 3, vmax=top / 3)
        axes[2].set_title("image - reference (red: extra, blue: missing)", fontsize=8)
        fig.colorbar(shown, ax=axes[2], fraction=0.046)
        for ax in axes:
            ax.set_xticks([])
            ax.set_yticks([])
        fig.tight_layout()
        fig.savefig(args.output, dpi=80)
        print("wrote " + args.output)


if __name__ == "__main__":
    main()
