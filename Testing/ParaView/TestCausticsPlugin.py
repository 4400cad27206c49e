"""The ParaView plugin's test, run by pvbatch (ctest label `paraview`, build-pv/):
loads the plugin, reads a glTF scene with ParaView's own glTF reader, shows its
floor as a plain surface and its ball as a "Caustics Surface" refractor in a
"Caustics Render View", renders it, and checks that
1. the caustic is there: under the ball the floor shows the light that came through
   the glass (the pass takes the ball's shadow off ParaView's unshadowed shading and
   adds the caustic): at least half as bright as with the view's caustics off
   (ParaView's own pass, which draws no shadow), and not the same as it;
2. the image matches the baseline PNG within a tolerance.

    pvbatch TestCausticsPlugin.py --plugin Caustics.so --scene ball-lens.gltf \
        --baseline TestCausticsPlugin.png --output-dir DIR [--technique screen-space]

--update-baseline writes the rendered image over the baseline instead of comparing.
Prints "TestCausticsPlugin: ok" on success; exits 1 on any failure.
"""
import argparse
import os
import shutil
import sys
import time

import paraview.simple as pvs
from vtkmodules.vtkCommonCore import vtkMath
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkRenderingCore import vtkCamera
from vtkmodules.util.numpy_support import vtk_to_numpy

# The built-in ball-lens scene's camera and light (vtkCausticsBuiltinScene).
CAMERA_POSITION = [0.0, 4.5, 9.0]
CAMERA_FOCAL_POINT = [0.0, 1.3, 0.0]
CAMERA_VIEW_ANGLE = 30.0
CAUSTIC_CENTRE = [0.0, 0.0, 0.0]  # on the floor, right under the ball
# Blocks of ParaView's glTF reader output: one per glTF node, in file order.
FLOOR_BLOCK = "/Root/Node_0"
BALL_BLOCK = "/Root/Node_1"


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--plugin", required=True, help="the plugin's shared library")
    parser.add_argument("--scene", required=True, help="glTF file (ball-lens.gltf)")
    parser.add_argument("--baseline", required=True, help="PNG the image is compared with")
    parser.add_argument("--output-dir", required=True, help="where the images are written")
    parser.add_argument("--technique", default="screen-space")
    parser.add_argument("--size", type=int, default=192, help="image side, pixels")
    parser.add_argument("--photons", type=int, default=128, help="photon grid side per light")
    parser.add_argument("--ior", type=float, default=1.5)
    parser.add_argument("--min-caustic-gain", type=float, default=0.5,
                        help="least ratio of the floor's brightness under the ball, "
                             "caustics on / off (0: a shadow and no caustic)")
    parser.add_argument("--min-caustic-change", type=float, default=0.1,
                        help="least |ratio - 1| (0: the pass changed nothing there)")
    parser.add_argument("--max-mean-error", type=float, default=1.0,
                        help="largest mean absolute difference to the baseline (0-255)")
    parser.add_argument("--max-bad-pixels", type=float, default=0.01,
                        help="largest fraction of pixels differing by more than 48 (0-255)")
    parser.add_argument("--update-baseline", action="store_true")
    parser.add_argument("--redistribute", action="store_true",
                        help="split the floor and the ball among the MPI ranks "
                             "(docs/paraview.md: the caustic is then not exact)")
    return parser.parse_args()


def build_scene(options):
    """The view, with the floor as a plain surface and the ball as a refractor."""
    pvs.LoadPlugin(options.plugin, ns=globals())
    pvs._DisableFirstRenderCameraReset()
    reader = pvs.glTFReader(FileName=options.scene)
    floor = pvs.ExtractBlock(Input=reader, Selectors=[FLOOR_BLOCK])
    ball = pvs.ExtractBlock(Input=reader, Selectors=[BALL_BLOCK])
    if options.redistribute:
        # Under MPI, split each object among the ranks (the reader puts all on rank 0).
        floor = pvs.RedistributeDataSet(Input=floor)
        ball = pvs.RedistributeDataSet(Input=ball)

    view = pvs.CreateView("CausticsRenderView")
    view.ViewSize = [options.size, options.size]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.05, 0.05, 0.06]
    # One directional light straight down, as in the glTF file (ParaView's glTF
    # reader does not read KHR_lights_punctual): the light kit off.
    view.UseLight = 0
    sun = pvs.AddLight(view=view)
    sun.Coords = "Scene"
    sun.Type = "Directional"
    sun.Position = [0.0, 1.0, 0.0]
    sun.FocalPoint = [0.0, 0.0, 0.0]
    sun.Intensity = 1.0

    floor_display = pvs.Show(floor, view)
    floor_display.ColorArrayName = [None, ""]
    # Mid grey, so that the caustic stays below white where the test measures it.
    floor_display.DiffuseColor = [0.5, 0.5, 0.5]
    floor_display.AmbientColor = [0.5, 0.5, 0.5]
    ball_display = pvs.Show(ball, view)
    ball_display.ColorArrayName = [None, ""]
    ball_display.SetRepresentationType("Caustics Surface")
    ball_display.CausticsRole = "Refractor"
    ball_display.CausticsIOR = options.ior

    view.CausticsTechnique = options.technique
    view.PhotonGridSide = options.photons
    view.CameraPosition = CAMERA_POSITION
    view.CameraFocalPoint = CAMERA_FOCAL_POINT
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraViewAngle = CAMERA_VIEW_ANGLE
    return view


def render(view, options, name):
    """Renders and saves DIR/<name>.png; returns the image as rows x columns x RGB."""
    path = os.path.join(options.output_dir, name + ".png")
    start = time.time()
    pvs.Render(view)
    pvs.SaveScreenshot(path, view, ImageResolution=[options.size, options.size])
    print("TestCausticsPlugin: %s rendered in %.1f s: %s" % (name, time.time() - start, path))
    return read_png(path)


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).astype(float)
    return pixels.reshape(height, width, -1)[:, :, :3]


def caustic_pixel(size):
    """Where CAUSTIC_CENTRE is in the image (column, row from the bottom)."""
    camera = vtkCamera()
    camera.SetPosition(CAMERA_POSITION)
    camera.SetFocalPoint(CAMERA_FOCAL_POINT)
    camera.SetViewUp(0.0, 1.0, 0.0)
    camera.SetViewAngle(CAMERA_VIEW_ANGLE)
    matrix = camera.GetCompositeProjectionTransformMatrix(1.0, -1.0, 1.0)
    clip = matrix.MultiplyPoint(CAUSTIC_CENTRE + [1.0])
    x, y = clip[0] / clip[3], clip[1] / clip[3]
    return int(round((x + 1.0) * 0.5 * size)), int(round((y + 1.0) * 0.5 * size))


def mean_luminance(image, column, row, half):
    window = image[max(0, row - half):row + half + 1, max(0, column - half):column + half + 1]
    return float((window * [0.2126, 0.7152, 0.0722]).sum(axis=2).mean())


def main():
    options = parse_arguments()
    os.makedirs(options.output_dir, exist_ok=True)
    failures = []
    view = build_scene(options)
    with_caustics = render(view, options, "TestCausticsPlugin")
    view.CausticsTechnique = "off"
    without = render(view, options, "TestCausticsPlugin-off")

    column, row = caustic_pixel(options.size)
    half = max(1, options.size // 64)
    lit, plain = (mean_luminance(image, column, row, half) for image in (with_caustics, without))
    gain = lit / max(plain, 1e-3)
    print("TestCausticsPlugin: floor under the ball (pixel %d, %d): %.1f with caustics, %.1f "
          "without, gain %.2f (least %.2f)" % (column, row, lit, plain, gain,
                                               options.min_caustic_gain))
    if not gain >= options.min_caustic_gain:
        failures.append("no caustic under the ball: gain %.2f < %.2f" %
                        (gain, options.min_caustic_gain))
    if not abs(gain - 1.0) >= options.min_caustic_change:
        failures.append("the pass left the floor under the ball as ParaView shades it: "
                        "gain %.2f within %.2f of 1" % (gain, options.min_caustic_change))

    if options.update_baseline:
        shutil.copyfile(os.path.join(options.output_dir, "TestCausticsPlugin.png"),
                        options.baseline)
        print("TestCausticsPlugin: baseline written: %s" % options.baseline)
    elif not os.path.exists(options.baseline):
        failures.append("no baseline %s (run with --update-baseline)" % options.baseline)
    else:
        baseline = read_png(options.baseline)
        if baseline.shape != with_caustics.shape:
            failures.append("image %s but baseline %s" % (with_caustics.shape, baseline.shape))
        else:
            difference = abs(with_caustics - baseline).max(axis=2)
            mean_error = float(difference.mean())
            bad = float((difference > 48).mean())
            print("TestCausticsPlugin: against the baseline: mean error %.2f (most %.2f), "
                  "pixels off by more than 48: %.4f (most %.4f)" %
                  (mean_error, options.max_mean_error, bad, options.max_bad_pixels))
            if mean_error > options.max_mean_error or bad > options.max_bad_pixels:
                failures.append("image differs from the baseline %s" % options.baseline)

    # Deleted here, with its window still whole: left to the interpreter's exit,
    # ParaView 5.11 tears the window down first and then makes its dead context
    # current to free the renderer's objects (an X error, exit code 1).
    pvs.Delete(view)
    del view

    for failure in failures:
        print("TestCausticsPlugin: FAILED: " + failure)
    if failures:
        sys.exit(1)
    print("TestCausticsPlugin: ok")


if __name__ == "__main__":
    main()
