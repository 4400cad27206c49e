#!/usr/bin/env python3
"""A mirror that lights nothing in view, far from a zoomed camera: prints, per
technique and mirror position, the relative L2 of the caustic irradiance and the flux
against the CPU reference of the scene without the mirror (the mirror sends its light
to the sky, so the caustic in view is the same), and the difference from the
technique's own caustic without the mirror (docs/accuracy.md, "Photons where the
camera looks").

    PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \\
        scripts/idle-mirror.py [--scene ball-lens] [--view-angle 12] [--mirrors 12,30] \\
        [--size 256] [--photons 256] [--reference-photons 4e6]

The mirror is a silver square 1 m wide facing up, 0.5 m above the floor, at x = each
of --mirrors (m). Needs the Python wrapping and a display or EGL.
"""
import argparse
import importlib.util
import os

import numpy

import vtkcaustics  # imports VTK's OpenGL2 rendering first
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location(
    "sweep", os.path.join(HERE, "reconstruction-sweep.py"))
sweep = importlib.util.module_from_spec(spec)
spec.loader.exec_module(sweep)


def add_mirror(renderer, x):
    plane = vtkPlaneSource()
    plane.SetOrigin(x, 0.5, -0.5)
    plane.SetPoint1(x + 1.0, 0.5, -0.5)
    plane.SetPoint2(x, 0.5, 0.5)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(plane.GetOutputPort())
    mirror = vtkActor()
    mirror.SetMapper(mapper)
    vtkcaustics.vtkCausticsMaterial.MakeMirror(
        mirror.GetProperty(), [0.155, 0.117, 0.138], [4.83, 3.12, 2.15])
    renderer.AddActor(mirror)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="ball-lens")
    parser.add_argument("--techniques", default="screen-space,caustic-maps")
    parser.add_argument("--view-angle", type=float, default=12.0)
    parser.add_argument("--mirrors", default="12,30")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--photons", type=int, default=256)
    parser.add_argument("--reference-photons", type=float, default=4e6)
    options = parser.parse_args()
    truth = None
    own = {}
    print("| mirror at x (m) | technique | relative L2 | flux / reference | "
          "difference from no mirror |")
    print("|---|---|---|---|---|")
    for x in [0.0] + [float(m) for m in options.mirrors.split(",")]:
        frame = sweep.Frame(options.scene, options.size)
        if x:
            add_mirror(frame.renderer, x)
        frame.renderer.GetActiveCamera().SetViewAngle(options.view_angle)
        frame.renderer.ResetCameraClippingRange()
        if truth is None:
            reference = vtkcaustics.vtkCausticsReferenceRenderer()
            reference.SetInputRenderer(frame.renderer)
            reference.SetImageSize(options.size, options.size)
            reference.SetPhotonsPerLight(int(options.reference_photons))
            reference.CameraSeesRefractorsOff()
            if not reference.Update():
                raise RuntimeError(reference.GetLastError())
            truth = reference.GetOutput()
        for technique in options.techniques.split(","):
            image, _ = frame.caustic(technique, "splats", options.photons, 1)
            metrics = vtkcaustics.vtkCausticsErrorMetrics()
            metrics.SetArrayName("CausticIrradiance")
            metrics.SetMaskArrayName("ReceiverMask")
            metrics.SetAreaArrayName("PixelArea")
            metrics.Compute(image, truth)
            values = sweep.channels(image, "CausticIrradiance")[..., :3].astype(float)
            alone = own.setdefault(technique, values)
            change = numpy.sqrt(((values - alone) ** 2).sum() / max((alone ** 2).sum(), 1e-300))
            print("| %s | %s | %.2f %% | %.4f | %.3g %% |" % (
                "none" if x == 0.0 else "%g" % x, technique,
                100.0 * metrics.GetRelativeL2Error(), metrics.GetFluxRatio(), 100.0 * change),
                flush=True)


if __name__ == "__main__":
    main()
