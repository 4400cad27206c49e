#!/usr/bin/env python3
"""Built-in scenes changed as a user might change them, each technique's caustic
irradiance against the CPU reference of the same view: the scene's lights replaced by
one lamp (--lamp X,Y,Z: a point light, or a spot light with --cone, aimed at --focal),
its glass or water made to absorb (--attenuation R,G,B, Beer-Lambert in 1/m), and a
glass ball added (--add-ball X,Y,Z,RADIUS, index 1.5). The figures behind
docs/accuracy.md, "Lamps", "Absorbing glass and water" and "Two pieces of glass".

    PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \\
        scripts/scene-variant.py --scene ball-lens [--lamp 0.5,6,0.3] \\
        [--attenuation 0.5,0.2,0.05] [--add-ball 0,1.2,0,0.5] \\
        [--techniques screen-space,caustic-maps,cascaded,impostors] [--cone DEGREES] \\
        [--size 256] [--photons 256] [--reference-photons 1.6e7] [--reference-kernel 1] \\
        [--intensity 50] [--array DirectIrradiance] [--reconstruction triangles] \\
        [--output PREFIX]

The reference's kernel decides how sharp a focus it shows: with the default of
caustics-render (two pixel footprints) a lamp's focus on the floor is half as bright as
with one. Scenes whose receivers lie under water (the pool) are compared with the
reference's camera rays passing the refractors, as the caustic buffer's G-buffer does
(--through-glass: every scene).
--array compares another buffer the reference also writes (DirectIrradiance: the
lights' shadowed irradiance). Prints relative L2, flux ratio, the ratio of the
brightest receiver pixels, the share of the caustic the technique's lost light could
be (GetLastFrameLostLightBound; it warns past 10 %) and the frame time (one frame after a first that compiles).
--reconstruction triangles draws caustic triangles instead of splats (screen-space, the
caustic maps and the impostors; cascaded keeps its splats and its row says so). --output PREFIX writes
PREFIX-reference.vti and PREFIX-TECHNIQUE.vti. Needs the Python wrapping and a display
or EGL.
"""
import argparse
import importlib.util
import os
import time

import numpy
import vtkcaustics  # imports VTK's OpenGL2 rendering first
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkLight, vtkPolyDataMapper

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location(
    "sweep", os.path.join(HERE, "reconstruction-sweep.py"))
sweep = importlib.util.module_from_spec(spec)
spec.loader.exec_module(sweep)

UNDER_WATER = {"pool"}
REFRACTOR = 3  # vtkCausticsMaterial's role


def triple(text):
    values = [float(v) for v in text.split(",")]
    if len(values) != 3:
        raise argparse.ArgumentTypeError("expected X,Y,Z")
    return values


def write(image, name):
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(name)
    writer.SetInputData(image)
    writer.Write()


def peak(image, array, truth):
    """The brightest receiver pixel (the reference's ReceiverMask: what the metrics compare)."""
    values = vtk_to_numpy(image.GetPointData().GetArray(array))
    mask = vtk_to_numpy(truth.GetPointData().GetArray("ReceiverMask")).reshape(len(values))
    return float(numpy.max(values.reshape(len(values), -1).sum(axis=1) * (mask > 0)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="ball-lens")
    parser.add_argument("--lamp", type=triple, help="a point light here replaces the scene's")
    parser.add_argument("--focal", type=triple, default=[0.0, 0.0, 0.0])
    parser.add_argument("--cone", type=float, default=180.0,
                        help="spot cone half angle in degrees (180: a point light)")
    parser.add_argument("--intensity", type=float, default=50.0, help="the lamp's")
    parser.add_argument("--attenuation", type=triple,
                        help="Beer-Lambert absorption of the scene's refractors, 1/m per channel")
    parser.add_argument("--techniques", default="screen-space,caustic-maps,cascaded,impostors")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--photons", type=int, default=256)
    parser.add_argument("--reference-photons", type=float, default=1.6e7)
    parser.add_argument("--reference-kernel", type=sweep.reference_kernel, default=1.0,
                        help="radius in pixel footprints, or pixel: the flux in each "
                        "pixel's footprint over its area")
    parser.add_argument("--add-ball", type=lambda text: [float(v) for v in text.split(",")],
                        help="X,Y,Z,RADIUS: a glass ball (index 1.5) added to the scene")
    parser.add_argument("--through-glass", action="store_true",
                        help="the reference's camera rays pass glass and water unbent, as "
                        "caustics-bench's ground truth (every scene's receivers, the floor "
                        "under the bunny too)")
    parser.add_argument("--array", default="CausticIrradiance")
    parser.add_argument("--reconstruction", choices=sorted(sweep.MODES), default="splats",
                        help="splats or caustic triangles (a technique without them, "
                        "cascaded, is marked and keeps its splats)")
    parser.add_argument("--output")
    options = parser.parse_args()

    frame = sweep.Frame(options.scene, options.size)  # the window and the built-in scene
    window, renderer = frame.window, frame.renderer
    if options.lamp:
        lamp = vtkLight()
        lamp.SetLightTypeToSceneLight()
        lamp.SetPositional(True)
        lamp.SetPosition(*options.lamp)
        lamp.SetFocalPoint(*options.focal)
        lamp.SetConeAngle(options.cone)
        lamp.SetIntensity(options.intensity)
        renderer.RemoveAllLights()
        renderer.AddLight(lamp)
    if options.add_ball:
        if len(options.add_ball) != 4:
            raise SystemExit("--add-ball: expected X,Y,Z,RADIUS")
        sphere = vtkSphereSource()
        sphere.SetCenter(*options.add_ball[:3])
        sphere.SetRadius(options.add_ball[3])
        sphere.SetThetaResolution(96)
        sphere.SetPhiResolution(48)
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(sphere.GetOutputPort())
        ball = vtkActor()
        ball.SetMapper(mapper)
        vtkcaustics.vtkCausticsMaterial.MakeGlass(ball.GetProperty(), 1.5)
        renderer.AddActor(ball)
        renderer.ResetCameraClippingRange()
    if options.attenuation:
        actors = renderer.GetActors()
        actors.InitTraversal()
        for _ in range(actors.GetNumberOfItems()):
            actor = actors.GetNextActor()
            if vtkcaustics.vtkCausticsMaterial.Classify(actor) == REFRACTOR:
                vtkcaustics.vtkCausticsMaterial.SetAttenuation(actor.GetProperty(),
                                                               options.attenuation)

    reference = vtkcaustics.vtkCausticsReferenceRenderer()
    reference.SetInputRenderer(renderer)
    reference.SetImageSize(options.size, options.size)
    reference.SetPhotonsPerLight(int(options.reference_photons))
    sweep.set_reference_kernel(reference, options.reference_kernel)
    reference.SetCameraSeesRefractors(options.scene not in UNDER_WATER and not options.through_glass)
    if not reference.Update():
        raise SystemExit(reference.GetLastError())
    truth = reference.GetOutput()
    if options.output:
        write(truth, options.output + "-reference.vti")

    changes = []
    if options.lamp:
        changes.append("lamp at (%s)" % ", ".join("%g" % v for v in options.lamp))
    if options.add_ball:
        changes.append("a glass ball at (%s), radius %g" % (
            ", ".join("%g" % v for v in options.add_ball[:3]), options.add_ball[3]))
    if options.reconstruction != "splats":
        changes.append(options.reconstruction)
    if options.attenuation:
        changes.append("absorbing (%s) 1/m" % ", ".join("%g" % v for v in options.attenuation))
    print("| %s | relative L2 | flux / reference | peak / reference's | lost-light bound | frame (ms) |"
          % ", ".join([options.scene] + changes))
    print("|---|--:|--:|--:|--:|--:|")
    for technique in options.techniques.split(","):
        caustics = vtkcaustics.vtkCausticsTechniques.NewPass(technique)
        caustics.KeepBuffersOn()
        caustics.SetLightBufferResolution(options.photons)
        name = technique
        if hasattr(caustics, "SetReconstruction"):
            caustics.SetReconstruction(sweep.MODES[options.reconstruction])
        elif options.reconstruction != "splats":
            name += " (splats: it has no triangles)"
        renderer.SetPass(caustics)
        window.Render()  # compiles
        start = time.perf_counter()
        window.Render()
        image = vtkImageData()
        if not caustics.ReadBuffer(options.array, image):  # waits for the GPU
            raise SystemExit("%s: no %s buffer" % (technique, options.array))
        seconds = time.perf_counter() - start
        lost = caustics.GetLastFrameLostLightBound()
        renderer.SetPass(None)
        caustics.ReleaseGraphicsResources(window)
        if options.output:
            write(image, "%s-%s.vti" % (options.output, technique))
        metrics = vtkcaustics.vtkCausticsErrorMetrics()
        metrics.SetArrayName(options.array)
        metrics.SetMaskArrayName("ReceiverMask")
        metrics.SetAreaArrayName("PixelArea")
        if not metrics.Compute(image, truth):
            print("| %s | no comparison (see the error above) | | | | |" % name)
            continue
        print("| %s | %.1f %% | %.3f | %.2f | %s | %.0f |" % (
            name, 100.0 * metrics.GetRelativeL2Error(), metrics.GetFluxRatio(),
            peak(image, options.array, truth) / max(peak(truth, options.array, truth), 1e-30),
            "%.1f %%" % (100.0 * lost) if lost >= 0.0 else "-", 1000.0 * seconds), flush=True)


if __name__ == "__main__":
    main()
