#!/usr/bin/env python3
"""How far one far-away actor can be before a technique's caustic loses detail
(docs/reliability.md, "Far-away actors"): renders the built-in ball lens with a
1 m cube added at each distance along x and prints the caustic's peak
(CausticIrradiance, 128 x 128 image, 128 x 128 photons) over the peak without it.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 scripts/far-actor-sweep.py \
        [--distances 30,60,100,300,1000,1500,2000,3000] [--techniques caustic-maps,screen-space]

Needs the Python wrapping (-DCAUSTICS_WRAP_PYTHON=ON) and a display or EGL.
"""
import argparse
import math

import vtkcaustics  # imports VTK's OpenGL2 rendering first
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersSources import vtkCubeSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer


def peak(technique, distance):
    """The caustic's peak (W/m^2) with the cube `distance` m away (0: no cube), and
    the scene's size over the specular actors'."""
    window = vtkcaustics.vtkCausticsWindowFactory().NewWindow(True)
    window.SetMultiSamples(0)
    window.SetSize(128, 128)
    renderer = vtkOpenGLRenderer()
    window.AddRenderer(renderer)
    scene = vtkcaustics.vtkCausticsBuiltinScene()
    if not scene.Populate(renderer):
        raise RuntimeError(scene.GetLastError())
    if distance > 0:
        cube = vtkCubeSource()
        cube.SetCenter(distance, 0.0, 0.0)
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(cube.GetOutputPort())
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer.AddActor(actor)
    caustics = vtkcaustics.vtkCausticsTechniques.NewPass(technique)
    caustics.KeepBuffersOn()
    caustics.SetLightBufferResolution(128)
    renderer.SetPass(caustics)
    window.Render()
    image = vtkImageData()
    if not caustics.ReadBuffer("CausticIrradiance", image):
        raise RuntimeError("no caustic buffer")
    value = float(vtk_to_numpy(image.GetPointData().GetArray(0)).max())
    ratio = caustics.GetLastSceneScaleRatio()
    renderer.SetPass(None)
    caustics.ReleaseGraphicsResources(window)
    return value, ratio


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--distances", default="30,60,100,300,1000,1500,2000,3000")
    parser.add_argument("--techniques", default="caustic-maps,screen-space")
    options = parser.parse_args()
    distances = [float(d) for d in options.distances.split(",")]
    print("| technique | " + " | ".join("%g m" % d for d in distances) + " |")
    print("|---" * (len(distances) + 1) + "|")
    for technique in options.techniques.split(","):
        clear, _ = peak(technique, 0.0)
        cells = []
        for d in distances:
            value, ratio = peak(technique, d)
            cells.append("%.2f (%.0f)" % (value / clear if clear > 0 else math.nan, ratio))
        print("| %s | %s |" % (technique, " | ".join(cells)))
    print("(peak over the peak without the cube; in brackets the scene's size over the "
          "specular actors')")


if __name__ == "__main__":
    main()
