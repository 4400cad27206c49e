#!/usr/bin/env python3
"""Caustics via distance impostors against the reference, frame by frame: renders a
built-in scene with the `impostors` technique at 256² pixels and 256² light-buffer
texels (as TestImpostorPhotonPass) and prints, after each frame, the relative L2 and
the flux ratio of the mean of the frames so far against the CPU reference (10⁶
photons, cached; receiver pixels, pixel areas for the flux). What falls with the
frames is the roulette's noise; what stays is the same every frame.

    PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \\
        scripts/impostor-frames.py [SCENE] [KERNEL_SPACINGS[,...]] [FRAMES] [--progressive]

Defaults: ball-lens, 2 (the default kernel), 4 frames. Without --progressive the script
averages frames of one light grid itself; with it, it reads the pass's own mean
(ProgressiveFrames = FRAMES), whose frames move the light grid by sub-texel offsets, as
TestImpostorPhotonPass does. Needs the Python wrapping
(-DCAUSTICS_WRAP_PYTHON=ON) and a display or EGL.
"""
import argparse

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy

import vtkcaustics  # imports VTK's OpenGL2 rendering first
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer

SIZE = 256


def array(image, name, components):
    return vtk_to_numpy(image.GetPointData().GetArray(name)).reshape(-1, components).astype(float)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene", nargs="?", default="ball-lens")
    parser.add_argument("spacings", nargs="?", default="2", help="KernelSpacings, comma-separated")
    parser.add_argument("frames", nargs="?", type=int, default=4)
    parser.add_argument("--progressive", action="store_true",
                        help="the pass's mean (ProgressiveFrames) instead of the script's")
    args = parser.parse_args()

    window = vtkcaustics.vtkCausticsWindowFactory().NewWindow(True)
    window.SetMultiSamples(0)
    window.SetSize(SIZE, SIZE)
    renderer = vtkOpenGLRenderer()
    window.AddRenderer(renderer)
    scene = vtkcaustics.vtkCausticsBuiltinScene()
    scene.SetSceneName(args.scene)
    if not scene.Populate(renderer):
        raise SystemExit(scene.GetLastError())

    reference = vtkcaustics.vtkCausticsReferenceRenderer()
    reference.SetInputRenderer(renderer)
    reference.SetImageSize(SIZE, SIZE)
    reference.SetPhotonsPerLight(1000000)
    reference.SetCameraSeesRefractors(True)
    if not reference.Update():
        raise SystemExit(reference.GetLastError())
    truth = reference.GetOutput()
    mask = array(truth, "ReceiverMask", 1)[:, 0] > 0
    area = array(truth, "PixelArea", 1)[:, 0][mask]
    expected = array(truth, "CausticIrradiance", 3)[mask]

    for spacings in (float(s) for s in args.spacings.split(",")):
        caustics = vtkcaustics.vtkCausticsTechniques.NewPass("impostors")
        caustics.KeepBuffersOn()
        caustics.SetLightBufferResolution(SIZE)
        caustics.SetKernelSpacings(spacings)
        if args.progressive:
            caustics.SetProgressiveFrames(args.frames)
        renderer.SetPass(caustics)
        total = numpy.zeros_like(expected)
        for frame in range(1, args.frames + 1):
            window.Render()
            image = vtkImageData()
            if not caustics.ReadBuffer("CausticIrradiance", image):
                raise SystemExit("impostor-frames: frame %d has no caustic" % frame)
            if args.progressive:
                mean = array(image, "CausticIrradiance", 3)[mask]  # the pass's mean
            else:
                total += array(image, "CausticIrradiance", 3)[mask]
                mean = total / frame
            l2 = numpy.sqrt(((mean - expected) ** 2).sum() / (expected ** 2).sum())
            flux = (mean.sum(1) * area).sum() / (expected.sum(1) * area).sum()
            print("%s KernelSpacings %g: mean of %d frame(s): relative L2 %.4f, flux %.4f"
                  % (args.scene, spacings, frame, l2, flux), flush=True)
        renderer.SetPass(None)
        caustics.ReleaseGraphicsResources(window)


if __name__ == "__main__":
    main()
