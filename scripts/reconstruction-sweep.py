#!/usr/bin/env python3
"""Splats against caustic triangles (vtkCausticsPhotonSplatter::SetReconstruction):
renders built-in scenes with the screen-space technique each way and prints, per
scene, the relative L2 of the caustic irradiance and the flux against the CPU
reference of the same frame (receiver pixels, vtkCausticsErrorMetrics), and the
median frame time over repeats. The reference estimates irradiance with an
Epanechnikov kernel of 2 pixel footprints (docs/reference.md), which blurs folds and
foci that triangles keep sharp; so the relative L2 is also given after blurring the
technique's image with that kernel in image space (a 2-pixel disk: the footprint's
disk for surfaces facing the camera, an approximation elsewhere).

    PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \\
        scripts/reconstruction-sweep.py [--scenes ball-lens,pool,ring,bunny] [--size 256] \\
        [--photons 256] [--reference-photons 4e6] [--reference-kernel 2] [--repeats 3]

Needs the Python wrapping (-DCAUSTICS_WRAP_PYTHON=ON) and a display or EGL.
"""
import argparse
import statistics
import time

import numpy
from scipy.ndimage import convolve
from vtkmodules.util.numpy_support import vtk_to_numpy

import vtkcaustics  # imports VTK's OpenGL2 rendering first
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer

MODES = {"splats": 0, "triangles": 1}


def channels(image, name):
    """The array `name` of a square image as (rows, columns, components)."""
    size = image.GetDimensions()[0]
    return vtk_to_numpy(image.GetPointData().GetArray(name)).reshape(size, size, -1)


def blurred_relative_l2(image, truth, radius=2.0):
    """Relative L2 on the reference's receiver pixels after the reference's kernel."""
    reach = int(numpy.ceil(radius))
    y, x = numpy.mgrid[-reach:reach + 1, -reach:reach + 1]
    d2 = (x * x + y * y) / (radius * radius)
    kernel = numpy.where(d2 < 1.0, 1.0 - d2, 0.0)
    kernel /= kernel.sum()
    mask = channels(truth, "ReceiverMask")[..., 0] > 0
    reference = channels(truth, "CausticIrradiance")[..., :3]
    test = channels(image, "CausticIrradiance")[..., :3]
    # Only the receiver pixels take part (the reference's kernel never reaches across to
    # a surface it does not show, such as the floor behind water).
    weight = convolve(mask.astype(float), kernel, mode="constant")
    smooth = numpy.stack([convolve(test[..., c] * mask, kernel, mode="constant")
                          for c in range(3)], -1) / numpy.maximum(weight, 1e-12)[..., None]
    difference = ((smooth - reference)[mask] ** 2).sum()
    return numpy.sqrt(difference / (reference[mask] ** 2).sum())


def reference_kernel(text):
    """A --reference-kernel value: a radius in pixel footprints, or "pixel"."""
    return text if text == "pixel" else float(text)


def set_reference_kernel(reference, kernel):
    if kernel == "pixel":
        reference.PixelFootprintEstimateOn()
    else:
        reference.SetKernelRadiusPixels(kernel)


class Frame:
    def __init__(self, scene, size):
        self.size = size
        self.window = vtkcaustics.vtkCausticsWindowFactory().NewWindow(True)
        self.window.SetMultiSamples(0)
        self.window.SetSize(size, size)
        self.renderer = vtkOpenGLRenderer()
        self.window.AddRenderer(self.renderer)
        self.scene = vtkcaustics.vtkCausticsBuiltinScene()
        self.scene.SetSceneName(scene)
        if not self.scene.Populate(self.renderer):
            raise RuntimeError(self.scene.GetLastError())

    def caustic(self, technique, mode, photons, repeats):
        """The caustic irradiance and the median frame time (s)."""
        caustics = vtkcaustics.vtkCausticsTechniques.NewPass(technique)
        caustics.KeepBuffersOn()
        caustics.SetLightBufferResolution(photons)
        caustics.SetReconstruction(MODES[mode])
        self.renderer.SetPass(caustics)
        self.window.Render()  # compiles
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            self.window.Render()
            caustics.ReadBuffer("CausticIrradiance", vtkImageData())  # waits for the GPU
            times.append(time.perf_counter() - start)
        image = vtkImageData()
        if not caustics.ReadBuffer("CausticIrradiance", image):
            raise RuntimeError("no caustic buffer")
        self.renderer.SetPass(None)
        caustics.ReleaseGraphicsResources(self.window)
        return image, statistics.median(times)

    def reference(self, photons, kernel=2.0):
        """The CPU reference; kernel: radius in pixel footprints, or "pixel" for the
        flux landing in each pixel's footprint (PixelFootprintEstimate)."""
        reference = vtkcaustics.vtkCausticsReferenceRenderer()
        reference.SetInputRenderer(self.renderer)
        reference.SetImageSize(self.size, self.size)
        reference.SetPhotonsPerLight(int(photons))
        set_reference_kernel(reference, kernel)
        if not reference.Update():
            raise RuntimeError(reference.GetLastError())
        return reference.GetOutput()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", default="ball-lens,pool,ring,bunny")
    parser.add_argument("--techniques", default="screen-space")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--photons", type=int, default=256)
    parser.add_argument("--reference-photons", type=float, default=4e6)
    parser.add_argument("--reference-kernel", type=reference_kernel, default=2.0,
                        help="the reference's kernel radius in pixel footprints (default 2; "
                        "the blurred column still blurs with 2), or pixel: the flux in each "
                        "pixel's footprint")
    parser.add_argument("--repeats", type=int, default=3)
    options = parser.parse_args()
    print("| scene | technique | reconstruction | relative L2 | blurred as the reference | "
          "flux / reference | frame (s) |")
    print("|---|---|---|---|---|---|---|")
    for scene in options.scenes.split(","):
        frame = Frame(scene, options.size)
        truth = frame.reference(options.reference_photons, options.reference_kernel)
        for technique in options.techniques.split(","):
            for mode in MODES:
                image, seconds = frame.caustic(technique, mode, options.photons, options.repeats)
                metrics = vtkcaustics.vtkCausticsErrorMetrics()
                metrics.SetArrayName("CausticIrradiance")
                metrics.SetMaskArrayName("ReceiverMask")
                metrics.SetAreaArrayName("PixelArea")
                metrics.Compute(image, truth)
                print("| %s | %s | %s | %.1f %% | %.1f %% | %.3f | %.3f |" % (scene, technique,
                    mode, 100.0 * metrics.GetRelativeL2Error(),
                    100.0 * blurred_relative_l2(image, truth), metrics.GetFluxRatio(), seconds),
                    flush=True)


if __name__ == "__main__":
    main()
