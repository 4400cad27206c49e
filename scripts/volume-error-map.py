#!/usr/bin/env python3
"""Where a technique's volume caustic differs from the reference's: noise or bias.

The comparison of TestVolumeLines (the pass's "VolumeRadiance" against the reference
renderer's "VolumeCausticRadiance", airlight off), split so that the causes can be told
apart:

- the reference's own noise: rendered with seeds 1 and 2 (cached in
  $CAUSTICS_REFERENCE_CACHE); their difference / sqrt 2 is one seed's noise, and their
  mean, with 1/sqrt 2 of it, is the reference the techniques are measured against;
- the techniques' noise: caustic maps and screen-space are deterministic, so their noise
  shows as the error falling with the photon grid; cascaded's frames are independent
  sample sets, so the mean of K frames shows it falling with K;
- like with like: the pass spreads its lines with a Gaussian of sigma pixels after a
  one-pixel rasterization (variance sigma^2 + 1/12 per axis), the reference with an
  Epanechnikov kernel of radius c pixel footprints (variance c^2 / 6): "matched" blurs
  the coarser of the two images by the Gaussian that brings it to the other's variance;
- bias: both matched images blurred by a wide Gaussian (--coarse, pixels): noise and
  kernel shape average out there, a wrong level or a missing shaft does not;
- where: the matched error's share and the total ratio by eighths of the image's rows.

  cd build && PYTHONPATH=lib/python3/dist-packages CAUSTICS_REFERENCE_CACHE=reference-cache \\
      xvfb-run -a /usr/bin/python3 ../scripts/volume-error-map.py underwater \\
      [--size 256] [--volume-photons 1000000] [--techniques caustic-maps,cascaded,screen-space]
      [--photons 128,256] [--blurs 0.61,1.5] [--frames 8] [--output DIR]

Writes DIR/SCENE-TECHNIQUE-PHOTONS-BLUR.png: reference | technique | difference (red:
extra, blue: missing), both at the matched resolution, square roots of the values
scaled by the reference's 99th percentile (the difference by a third of it).
"""
import argparse
import importlib.util
import math
import os
import time

import numpy as np
import OpenImageIO as oiio
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderWindow
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer

import vtkcaustics

# The reference's render (seed, size, photon counts): reference-noise.py's.
_spec = importlib.util.spec_from_file_location(
    "reference_noise", os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                    "reference-noise.py"))
reference_noise = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(reference_noise)

KERNEL_RADIUS = 1.5  # the reference's VolumeKernelRadiusPixels (default)


def gaussian(image, sigma):
    """vtkCausticsVolumeLinesBlurCS's separable Gaussian: radius ceil(3 sigma), weights
    normalized over the taps inside the image."""
    if sigma <= 0.0:
        return image
    radius = int(math.ceil(3.0 * sigma))
    k = np.arange(-radius, radius + 1)
    w = np.exp(-0.5 * k * k / (sigma * sigma))

    def blur(values):
        for axis in (0, 1):
            pad = [(radius, radius) if a == axis else (0, 0) for a in range(values.ndim)]
            padded = np.pad(values, pad)
            values = sum(w[i] * np.take(padded, range(i, i + values.shape[axis]), axis=axis)
                         for i in range(2 * radius + 1))
        return values

    return blur(image) / blur(np.ones(image.shape[:2]))[:, :, None]


def rel(a, b):
    norm = (b ** 2).sum()
    return math.sqrt(((a - b) ** 2).sum() / norm) if norm > 0 else float("nan")


def reference(renderer, args, seed):
    """The reference's volume caustic, rows x columns x RGB."""
    options = argparse.Namespace(size=args.size, photons=10000,
                                 volume_photons=args.volume_photons,
                                 array="VolumeCausticRadiance")
    start = time.time()
    image = reference_noise.render(renderer, options, seed)
    print(f"  reference seed {seed}: {args.volume_photons} volume photons, "
          f"{time.time() - start:.1f} s (cached entries load in well under a second)")
    return image.reshape(args.size, args.size, -1)[:, :, :3]


def technique_frames(renderer, window, name, photons, blur, frames):
    """Each frame's volume layer (airlight off), as TestVolumeLines renders it."""
    technique = vtkcaustics.vtkCausticsTechniques.NewPass(name)
    technique.SetLightBufferResolution(photons)
    if name == "screen-space":
        technique.SetGodRayBlurPixels(blur)
    else:
        technique.SetVolumeBlurPixels(blur)
    if name == "cascaded":
        technique.SetNumberOfPhotons(photons * photons)
        technique.DenoiseOff()
    technique.GetAirlight().EnabledOff()
    technique.KeepBuffersOn()
    renderer.SetPass(technique)
    images = []
    for _ in range(frames):
        window.Render()
        image = vtkImageData()
        if not technique.ReadBuffer("VolumeRadiance", image):
            raise SystemExit(f"{name}: no volume layer")
        data = vtk_to_numpy(image.GetPointData().GetArray(0)).astype(np.float64)
        images.append(data.reshape(window.GetSize()[1], window.GetSize()[0], -1)[:, :, :3])
    renderer.SetPass(None)
    technique.ReleaseGraphicsResources(window)
    return images


def matched(image, truth, blur, kernel):
    """Both at the coarser one's per-axis variance (see the module's doc)."""
    gap = blur * blur + 1.0 / 12.0 - kernel * kernel / 6.0
    if gap >= 0.0:
        return image, gaussian(truth, math.sqrt(gap))
    return gaussian(image, math.sqrt(-gap)), truth


def write_map(path, truth, shown):
    top = max(float(np.percentile(truth, 99)), 1e-30)
    difference = (shown - truth).mean(axis=-1)
    diff = np.stack([np.clip(difference / (top / 3), 0, 1), np.zeros_like(difference),
                     np.clip(-difference / (top / 3), 0, 1)], axis=-1)
    row = np.concatenate([np.clip(truth / top, 0, 1), np.clip(shown / top, 0, 1), diff],
                         axis=1)[::-1]
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(row.shape[1], row.shape[0], 3, oiio.UINT8))
    out.write_image(np.ascontiguousarray((np.sqrt(row) * 255).astype(np.uint8)))
    out.close()


def report(label, shown, seeds, blur, args):
    """One line of figures and, by rows of the image, where the squared error sits."""
    truth = 0.5 * (seeds[0] + seeds[1])
    a, b = matched(shown, truth, blur, KERNEL_RADIUS)
    # The reference's noise at the matched resolution: one seed's, and the mean's.
    floor = rel(matched(shown, seeds[0], blur, KERNEL_RADIUS)[1],
                matched(shown, seeds[1], blur, KERNEL_RADIUS)[1]) / math.sqrt(2.0)
    coarse = rel(gaussian(a, args.coarse), gaussian(b, args.coarse))
    print(f"  {label}: total {shown.sum() / truth.sum():.4f}, relative L2 {rel(shown, truth):.4f}, "
          f"matched {rel(a, b):.4f} (the reference's noise there: one seed {floor:.4f}, the "
          f"mean {floor / math.sqrt(2.0):.4f}), coarse ({args.coarse} px) {coarse:.4f}")
    squared = ((a - b) ** 2).sum(axis=(1, 2))
    bands = np.array_split(np.arange(args.size), 8)
    shares = [squared[band].sum() / max(squared.sum(), 1e-300) for band in bands]
    ratios = [a[band].sum() / max(b[band].sum(), 1e-300) for band in bands]
    print("    matched error by eighths of the image, bottom to top (share, total ratio): " +
          ", ".join(f"{100 * s:.0f} % {r:.3f}" for s, r in zip(shares, ratios)))
    return a, b


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?", default="underwater")
    parser.add_argument("--size", type=int, default=256, help="image side, pixels")
    parser.add_argument("--volume-photons", type=int, default=1000000,
                        help="the reference's volume photons per seed")
    parser.add_argument("--techniques", default="caustic-maps,cascaded,screen-space")
    parser.add_argument("--photons", default="128,256", help="photon grids N (N x N)")
    parser.add_argument("--blurs", default="0.61,1.5", help="the pass's Gaussian, pixels")
    parser.add_argument("--frames", type=int, default=8, help="cascaded: frames averaged")
    parser.add_argument("--coarse", type=float, default=4.0, help="the bias check's blur, px")
    parser.add_argument("--output", default="volume-error-map")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)

    renderer = vtkOpenGLRenderer()
    scene = vtkcaustics.vtkCausticsBuiltinScene()
    scene.SetSceneName(args.scene)
    if not scene.Populate(renderer):
        raise SystemExit(scene.GetLastError())
    print(f"{args.scene} at {args.size}^2:")
    one, two = reference(renderer, args, 1), reference(renderer, args, 2)
    truth = 0.5 * (one + two)
    noise = rel(one, two) / math.sqrt(2.0)
    print(f"  reference noise per seed {noise:.4f}, of the two seeds' mean {noise / math.sqrt(2):.4f};"
          f" coarse ({args.coarse} px) per seed "
          f"{rel(gaussian(one, args.coarse), gaussian(two, args.coarse)) / math.sqrt(2):.4f}")

    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    for name in args.techniques.split(","):
        for photons in (int(p) for p in args.photons.split(",")):
            for blur in (float(s) for s in args.blurs.split(",")):
                frames = args.frames if name == "cascaded" else 1
                start = time.time()
                images = technique_frames(renderer, window, name, photons, blur, frames)
                seconds = time.time() - start
                shown = np.mean(images, axis=0)
                label = f"{name}, {photons}^2 photons, blur {blur} px"
                if frames > 1:
                    label += f", mean of {frames} frames"
                    single = np.mean([rel(image, truth) for image in images])
                    print(f"  {name}, {photons}^2 photons, blur {blur} px: one frame's "
                          f"relative L2 {single:.4f} (mean over {frames})")
                a, b = report(label + f" ({seconds:.0f} s)", shown, (one, two), blur, args)
                write_map(os.path.join(args.output, f"{args.scene}-{name}-{photons}-{blur}.png"),
                          b, a)
    print(f"wrote reference | technique | difference images to {args.output}/")


if __name__ == "__main__":
    main()
