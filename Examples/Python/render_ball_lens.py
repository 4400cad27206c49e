#!/usr/bin/env python3
"""Renders a built-in scene (the ball lens by default) to a PNG and a multi-layer
EXR, on any machine: with no X server the window is a headless EGL context (Mesa's
llvmpipe, or a GPU's EGL device), with no Xvfb needed.

    PYTHONPATH=<prefix>/lib/python3/dist-packages python3 render_ball_lens.py \
        [--output ball-lens] [--size 256] [--scene ball-lens] [--technique best]

The EXR holds what caustics-render writes: R,G,B (the picture), direct.* and
caustic.* (irradiance in W/m^2 before albedo), mask.Y (diffuse receivers).
"""
import argparse
import sys

import vtkcaustics  # imports VTK's OpenGL2 rendering first
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer


def read_buffer(caustics, name, image):
    """Adds the pass's buffer `name` to `image` as an array of that name."""
    buffer = vtkImageData()
    if not caustics.ReadBuffer(name, buffer):
        return False
    array = buffer.GetPointData().GetArray(0)
    array.SetName(name)
    image.GetPointData().AddArray(array)
    return True


def render(options):
    # The factory picks the window: X when DISPLAY is set, headless EGL otherwise.
    factory = vtkcaustics.vtkCausticsWindowFactory()
    window = factory.NewWindow(True)
    if window is None:
        raise RuntimeError(factory.GetLastError())
    window.SetMultiSamples(0)
    window.SetSize(options.size, options.size)
    renderer = vtkOpenGLRenderer()
    window.AddRenderer(renderer)

    scene = vtkcaustics.vtkCausticsBuiltinScene()
    scene.SetSceneName(options.scene)
    if not scene.Populate(renderer):
        raise RuntimeError(scene.GetLastError())
    caustics = vtkcaustics.vtkCausticsTechniques.NewPass(options.technique)
    if caustics is None:
        raise RuntimeError("unknown technique '%s' (known: %s)" % (
            options.technique, ", ".join(vtkcaustics.vtkCausticsTechniques.GetNames())))
    caustics.KeepBuffersOn()
    caustics.ComputeDirectIrradianceOn()
    renderer.SetPass(caustics)
    window.Render()

    image = vtkImageData()
    image.SetDimensions(options.size, options.size, 1)
    if not read_buffer(caustics, "FinalColor", image):
        raise RuntimeError("the frame produced no image")
    layers = [("FinalColor", "")]
    for name, layer in (("DirectIrradiance", "direct"), ("CausticIrradiance", "caustic"),
                        ("ReceiverMask", "mask")):
        if read_buffer(caustics, name, image):
            layers.append((name, layer))
    renderer.SetPass(None)
    caustics.ReleaseGraphicsResources(window)
    return image, layers, factory.GetLastPath()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--output", default="ball-lens", help="PATH: writes PATH.png and PATH.exr")
    parser.add_argument("--size", type=int, default=256, help="image width and height (pixels)")
    parser.add_argument("--scene", default="ball-lens",
                        choices=vtkcaustics.vtkCausticsBuiltinScene.GetSceneNames())
    parser.add_argument("--technique", default="best")
    parser.add_argument("--exposure", type=float, default=1.0)
    options = parser.parse_args()
    try:
        image, layers, window = render(options)
    except RuntimeError as error:
        print("render_ball_lens.py: error: %s" % error, file=sys.stderr)
        return 1

    io = vtkcaustics.vtkCausticsImageIO()
    png, exr = options.output + ".png", options.output + ".exr"
    if (not io.WritePNGFile(image, "FinalColor", png, options.exposure, False)
            or not io.WriteEXRFile(image, [a for a, _ in layers], [l for _, l in layers], exr)):
        print("render_ball_lens.py: error: " + io.GetLastError(), file=sys.stderr)
        return 1
    print("render_ball_lens.py: %s, technique %s, %dx%d, window %s" % (
        options.scene, options.technique, options.size, options.size, window))
    print("wrote %s and %s (layers: %s)" % (png, exr, ", ".join(l or "RGB" for _, l in layers)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
