#!/usr/bin/env python3
"""Where a technique's caustic irradiance differs from the reference's, and how much.

    error-map.py REFERENCE.exr IMAGE.exr [--blocks 16] [--blur SIGMA] [--output error-map.png]

REFERENCE.exr: a vtkCausticsReferenceRenderer image, either caustics-bench's cached
ground truth (`<build>/reference-cache/reference-<hash>.exr`, the hash in the generated
table of docs/benchmarks.md: CausticIrradiance, ReceiverMask, PixelArea) or the
`PREFIX-reference.exr` of `caustics-render --reference` (caustic, mask; no pixel areas,
so every receiver pixel weighs the same).
IMAGE.exr: the technique's caustic irradiance, as `caustics-bench --images` writes it
(layer `caustic`), or a caustics-render EXR (same layer name).

Prints the relative L2 error and flux ratio on the reference's receiver pixels,
weighted by pixel area where the reference has it (as vtkCausticsErrorMetrics; the
benchmark's figures come from that class), how much of the squared error is missing
light (image below the reference) or extra light, and the blocks of the image that
hold most of it (x, y in pixels from the top-left corner). With --output, a PNG of
the reference, the image and their signed difference (needs matplotlib).

--blur SIGMA compares both images blurred alike by a Gaussian of SIGMA pixels over
the receiver pixels (a normalized convolution, so that no light leaks off them): the
error at features wider than a few pixels, where two estimates with different
kernels (the reference's, a technique's splats) may disagree at sub-pixel detail.

Reads EXR with OpenImageIO's Python module (Debian: python3-openimageio).
"""
import argparse
import os
import sys

import numpy as np


class Layers:
    """The channels of one EXR by name, as float64 arrays, row 0 at the top."""

    def __init__(self, path):
        try:
            import OpenImageIO as oiio
        except ImportError:
            sys.exit("error-map: needs OpenImageIO's Python module (Debian: python3-openimageio)")
        image = oiio.ImageInput.open(path)
        if image is None:
            sys.exit("error-map: cannot read %s: %s" % (path, oiio.geterror()))
        spec = image.spec()
        pixels = image.read_image(format=oiio.FLOAT)
        image.close()
        if pixels is None:
            sys.exit("error-map: cannot read the pixels of " + path)
        pixels = np.asarray(pixels, dtype=np.float64).reshape(spec.height, spec.width,
                                                              spec.nchannels)
        self.path = path
        self.channels = {name: pixels[..., k] for k, name in enumerate(spec.channelnames)}

    def has(self, name):
        return name in self.channels

    def channel(self, name):
        if name not in self.channels:
            sys.exit("error-map: %s has no channel %s (it has %s)" %
                     (self.path, name, ", ".join(sorted(self.channels))))
        return self.channels[name]

    def rgb(self, layer):
        return np.stack([self.channel(layer + "." + c) for c in "RGB"], axis=-1)


def reference_layers(path):
    """Caustic irradiance, receiver mask and pixel weights of either reference layout."""
    layers = Layers(path)
    if layers.has("CausticIrradiance.R"):
        return (layers.rgb("CausticIrradiance"), layers.channel("ReceiverMask.Y") > 0.5,
                layers.channel("PixelArea.Y"))
    mask = layers.channel("mask.Y") > 0.5
    return layers.rgb("caustic"), mask, np.ones(mask.shape)


def blur_over(image, mask, sigma):
    """`image` (H x W x C) blurred by a Gaussian of `sigma` pixels over the pixels of
    `mask`, each normalized by the mask's own blur; zero off the mask."""
    radius = max(1, int(np.ceil(3.0 * sigma)))
    x = np.arange(-radius, radius + 1, dtype=np.float64)
    kernel = np.exp(-0.5 * (x / sigma) ** 2)
    kernel /= kernel.sum()

    def separable(a):
        for axis in (0, 1):
            a = np.apply_along_axis(lambda line: np.convolve(line, kernel, mode="same"), axis, a)
        return a

    inside = mask.astype(np.float64)
    weight = separable(inside)
    out = np.stack([separable(image[..., c] * inside) for c in range(image.shape[-1])], axis=-1)
    return np.where(mask[..., None], out / np.maximum(weight, 1e-12)[..., None], 0.0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("reference")
    parser.add_argument("image")
    parser.add_argument("--blocks", type=int, default=16, help="block size in pixels")
    parser.add_argument("--top", type=int, default=5, help="blocks to list")
    parser.add_argument("--output", help="PNG of reference, image and difference")
    parser.add_argument("--blur", type=float, default=0.0,
                        help="compare both blurred by a Gaussian of this many pixels")
    args = parser.parse_args()
    for path in (args.reference, args.image):
        if not os.path.isfile(path):
            sys.exit("error-map: no such file: " + path)

    truth, mask, area = reference_layers(args.reference)
    test = Layers(args.image).rgb("caustic")
    if truth.shape != test.shape:
        sys.exit("error-map: the images differ in size: %s and %s" %
                 (truth.shape[:2], test.shape[:2]))

    if args.blur < 0.0:
        sys.exit("error-map: --blur must be at least 0")
    if args.blur > 0.0:
        truth = blur_over(truth, mask, args.blur)
        test = blur_over(test, mask, args.blur)
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
