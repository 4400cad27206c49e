#!/usr/bin/env python3
"""Why caustic maps turn their view towards receivers the light grazes
(vtkCausticsHierarchicalCausticMapPass::SetMinimumMapIncidence, docs/reliability.md,
"A light grazing the receivers"): renders the built-in ball lens under a sun at each
elevation above the floor with each minimum angle of the map's view (0: the paper's
light view) and prints the relative L2 of the caustic irradiance against the CPU
reference of the same frame (128 x 128 image, 256 x 256 photons, receiver pixels,
vtkCausticsErrorMetrics).

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 scripts/map-incidence-sweep.py \
        [--elevations 0,2.9,8,20,30] [--minimums 0,20,30,45,60] [--reference-photons 4e6]

Needs the Python wrapping (-DCAUSTICS_WRAP_PYTHON=ON) and a display or EGL.
"""
import argparse
import math

import vtkcaustics  # imports VTK's OpenGL2 rendering first
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer


class Frame:
    """The ball lens under a sun `elevation` degrees above the floor."""

    def __init__(self, elevation):
        self.window = vtkcaustics.vtkCausticsWindowFactory().NewWindow(True)
        self.window.SetMultiSamples(0)
        self.window.SetSize(128, 128)
        self.renderer = vtkOpenGLRenderer()
        self.window.AddRenderer(self.renderer)
        self.scene = vtkcaustics.vtkCausticsBuiltinScene()
        if not self.scene.Populate(self.renderer):
            raise RuntimeError(self.scene.GetLastError())
        sun = self.renderer.GetLights().GetItemAsObject(0)
        e = math.radians(elevation)
        sun.SetFocalPoint(0.0, 0.0, 0.0)
        sun.SetPosition(-math.cos(e), math.sin(e), 0.0)

    def caustic(self, minimum):
        """The caustic-map frame's caustic irradiance with MinimumMapIncidence = minimum."""
        caustics = vtkcaustics.vtkCausticsTechniques.NewPass("caustic-maps")
        caustics.KeepBuffersOn()
        caustics.SetLightBufferResolution(256)
        caustics.SetMinimumMapIncidence(minimum)
        self.renderer.SetPass(caustics)
        self.window.Render()
        image = vtkImageData()
        if not caustics.ReadBuffer("CausticIrradiance", image):
            raise RuntimeError("no caustic buffer")
        self.renderer.SetPass(None)
        caustics.ReleaseGraphicsResources(self.window)
        return image

    def reference(self, photons):
        reference = vtkcaustics.vtkCausticsReferenceRenderer()
        reference.SetInputRenderer(self.renderer)
        reference.SetImageSize(128, 128)
        reference.SetPhotonsPerLight(int(photons))
        if not reference.Update():
            raise RuntimeError(reference.GetLastError())
        return reference.GetOutput()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--elevations", default="0,2.9,8,20,30")
    parser.add_argument("--minimums", default="0,20,30,45,60")
    parser.add_argument("--reference-photons", type=float, default=4e6)
    options = parser.parse_args()
    minimums = [float(m) for m in options.minimums.split(",")]
    print("| sun above the floor | " + " | ".join("%g" % m for m in minimums) + " |")
    print("|---" * (len(minimums) + 1) + "|")
    for elevation in [float(e) for e in options.elevations.split(",")]:
        frame = Frame(elevation)
        truth = frame.reference(options.reference_photons)
        cells = []
        for minimum in minimums:
            metrics = vtkcaustics.vtkCausticsErrorMetrics()
            metrics.SetArrayName("CausticIrradiance")
            metrics.SetMaskArrayName("ReceiverMask")
            metrics.SetAreaArrayName("PixelArea")
            metrics.Compute(frame.caustic(minimum), truth)
            cells.append("%.1f %%" % (100.0 * metrics.GetRelativeL2Error()))
        print("| %g° | %s |" % (elevation, " | ".join(cells)), flush=True)
    print("(relative L2 of the caustic against the reference, per minimum angle of the "
          "map's view in degrees; 0 is the light's own view)")


if __name__ == "__main__":
    main()
