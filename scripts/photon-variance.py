#!/usr/bin/env python3
"""How well a technique's own variance estimate matches its real frame-to-frame noise.

The shared deposit stages write, beside the raw caustic irradiance, the difference
of the luminance estimates of the frame's two halves of photons
(ReadBuffer("PhotonHalfSetDifference"); CausticsDeposit in vtkCausticsCommon.glsl).
Its square is the variance the SVGF denoiser takes for a short history. This renders
a still scene for N frames with the denoiser off, and prints, on the pixels with a
caustic (mean above 5 % of the largest), the median of (estimated variance / the
variance of the luminance over the frames), with its quartiles. 1 is a perfect
estimate; above 1 the denoiser blurs more than it needs to. Only techniques whose
photons change from frame to frame (cascaded: a rotated R2 sequence) have a
frame-to-frame variance to compare with.

  cd build && PYTHONPATH=lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \\
      ../scripts/photon-variance.py [--scene pool] [--technique cascaded] [--frames 24]
"""
import argparse

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderWindow
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer

import vtkcaustics

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def read(technique, name, size):
    image = vtkImageData()
    if not technique.ReadBuffer(name, image):
        raise SystemExit(f"no buffer {name}")
    return vtk_to_numpy(image.GetPointData().GetArray(0)).reshape(size, size, -1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="pool")
    parser.add_argument("--technique", default="cascaded")
    parser.add_argument("--frames", type=int, default=24)
    parser.add_argument("--size", type=int, default=128)
    args = parser.parse_args()

    renderer = vtkOpenGLRenderer()
    window = vtkRenderWindow()
    scene = vtkcaustics.vtkCausticsBuiltinScene()
    scene.SetSceneName(args.scene)
    if not scene.Populate(renderer):
        raise SystemExit(scene.GetLastError())
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    technique = vtkcaustics.vtkCausticsTechniques.NewPass(args.technique)
    if technique is None:
        raise SystemExit(f"no technique {args.technique}")
    technique.SetDenoise(False)
    technique.KeepBuffersOn()
    renderer.SetPass(technique)

    luminance, estimate = [], []
    for _ in range(args.frames):
        window.Render()
        luminance.append(read(technique, "RawCausticIrradiance", args.size) @ LUMINANCE)
        estimate.append(read(technique, "PhotonHalfSetDifference", args.size)[:, :, 0] ** 2)
    renderer.SetPass(None)
    technique.ReleaseGraphicsResources(window)

    luminance = np.array(luminance)
    mean = luminance.mean(axis=0)
    variance = luminance.var(axis=0, ddof=1)
    estimated = np.array(estimate).mean(axis=0)
    lit = mean > 0.05 * mean.max()
    if not (variance[lit] > 0).any():
        print(f"{args.scene}, {args.technique}: the estimate does not change between frames; "
              "nothing to compare with")
        return
    lit &= variance > 0
    ratio = estimated[lit] / variance[lit]
    q1, median, q3 = np.percentile(ratio, [25, 50, 75])
    print(f"{args.scene}, {args.technique}, {args.frames} frames at {args.size}^2: "
          f"{int(lit.sum())} caustic pixels; estimated / real variance: median {median:.3g} "
          f"(quartiles {q1:.3g}, {q3:.3g})")


if __name__ == "__main__":
    main()
