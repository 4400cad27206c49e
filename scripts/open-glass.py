#!/usr/bin/env python3
"""An open refractor that is not a sheet: half a glass sphere (radius 0.6 m, centre
1 m up, n = 1.5; vtkSphereSource with EndTheta 180), open along a vertical plane,
added beside the ball lens. Prints each technique's relative L2 of the caustic
irradiance, its flux against the CPU reference, and its median frame time: the case
behind the "open refractor that is not a sheet" row of docs/benchmarks.md ("Which
technique is best").

    PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \\
        scripts/open-glass.py [--techniques screen-space,caustic-maps] [--size 256] \\
        [--photons 256] [--reference-photons 4e6] [--repeats 3]

Needs the Python wrapping and a display or EGL.
"""
import argparse
import importlib.util
import os

import vtkcaustics  # imports VTK's OpenGL2 rendering first
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location(
    "sweep", os.path.join(HERE, "reconstruction-sweep.py"))
sweep = importlib.util.module_from_spec(spec)
spec.loader.exec_module(sweep)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--techniques", default="screen-space,caustic-maps")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--photons", type=int, default=256)
    parser.add_argument("--reference-photons", type=float, default=4e6)
    parser.add_argument("--repeats", type=int, default=3)
    options = parser.parse_args()
    frame = sweep.Frame("ball-lens", options.size)
    cap = vtkSphereSource()
    cap.SetEndTheta(180.0)
    cap.SetCenter(1.8, 1.0, 0.0)
    cap.SetRadius(0.6)
    cap.SetThetaResolution(64)
    cap.SetPhiResolution(32)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(cap.GetOutputPort())
    glass = vtkActor()
    glass.SetMapper(mapper)
    vtkcaustics.vtkCausticsMaterial.MakeGlass(glass.GetProperty(), 1.5)
    frame.renderer.AddActor(glass)
    frame.renderer.ResetCameraClippingRange()
    truth = frame.reference(options.reference_photons)
    print("| technique | relative L2 | flux / reference | frame (ms) |")
    print("|---|---|---|---|")
    for technique in options.techniques.split(","):
        image, seconds = frame.caustic(technique, "splats", options.photons, options.repeats)
        metrics = vtkcaustics.vtkCausticsErrorMetrics()
        metrics.SetArrayName("CausticIrradiance")
        metrics.SetMaskArrayName("ReceiverMask")
        metrics.SetAreaArrayName("PixelArea")
        metrics.Compute(image, truth)
        print("| %s | %.2f %% | %.4f | %.0f |" % (technique, 100.0 * metrics.GetRelativeL2Error(),
              metrics.GetFluxRatio(), 1000.0 * seconds), flush=True)


if __name__ == "__main__":
    main()
