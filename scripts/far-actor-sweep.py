#!/usr/bin/env python3
"""What one far-away actor does to a technique's caustic (docs/reliability.md,
"Far-away actors"): renders the built-in ball lens with a 1 m cube added at each
distance along x and prints the caustic's peak (CausticIrradiance, 128 x 128
image, 128 x 128 photons) over the peak without it. The cube stays out of the
camera's view. With --show-cube the camera is pulled back (ResetCamera) to show
it, which shrinks the caustic in the image, so each frame is compared with the
CPU reference of the same view instead (10^6 photons): relative L2 and flux
ratio over receiver pixels (vtkCausticsErrorMetrics), as the size of what the
camera sees grows against the specular actors'.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 scripts/far-actor-sweep.py \
        [--distances 30,60,100,300,1000,1500,2000,3000] [--techniques caustic-maps,screen-space] \
        [--show-cube]

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


def peak(technique, distance, show):
    """The caustic's peak (W/m^2) with the cube `distance` m away (0: no cube; shown:
    the camera pulled back to it), and the seen part's size over the specular actors'."""
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
        if show:
            renderer.ResetCamera()
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
    if show and distance > 0:
        reference = vtkcaustics.vtkCausticsReferenceRenderer()
        reference.SetInputRenderer(renderer)
        reference.SetImageSize(128, 128)
        reference.SetPhotonsPerLight(1000000)
        if not reference.Update():
            raise RuntimeError(reference.GetLastError())
        metrics = vtkcaustics.vtkCausticsErrorMetrics()
        metrics.SetArrayName("CausticIrradiance")
        metrics.SetMaskArrayName("ReceiverMask")
        metrics.SetAreaArrayName("PixelArea")
        # NaN, NaN when no receiver pixel is left (the floor smaller than a pixel).
        metrics.Compute(image, reference.GetOutput())
        value = (metrics.GetRelativeL2Error(), metrics.GetFluxRatio())
    renderer.SetPass(None)
    caustics.ReleaseGraphicsResources(window)
    return value, ratio


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--distances", default="30,60,100,300,1000,1500,2000,3000")
    parser.add_argument("--techniques", default="caustic-maps,screen-space")
    parser.add_argument("--show-cube", action="store_true",
                        help="pull the camera back to show the cube")
    options = parser.parse_args()
    distances = [float(d) for d in options.distances.split(",")]
    print("| technique | " + " | ".join("%g m" % d for d in distances) + " |")
    print("|---" * (len(distances) + 1) + "|")
    for technique in options.techniques.split(","):
        clear, _ = peak(technique, 0.0, False)
        cells = []
        for d in distances:
            value, ratio = peak(technique, d, options.show_cube)
            if options.show_cube:
                cells.append("%.3f, %.2f (%.0f)" % (value[0], value[1], ratio))
            else:
                cells.append("%.2f (%.0f)" % (value / clear if clear > 0 else math.nan, ratio))
        print("| %s | %s |" % (technique, " | ".join(cells)))
    if options.show_cube:
        print("(relative L2 and flux ratio against the reference of the same view; in "
              "brackets the size of what the camera sees over the specular actors')")
    else:
        print("(peak over the peak without the cube; in brackets the size of what the "
              "camera sees over the specular actors')")


if __name__ == "__main__":
    main()
