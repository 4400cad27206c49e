#!/usr/bin/env python3
"""What the camera sees from inside a refractor, against the reference.

With the eye inside glass or water, the first refractor surface a pixel sees is the
way out (the camera-view stage finds a closed refractor around the eye by its winding
number, else reads it per pixel from the first refractor surface seen from its back
side, as under the pool's open water sheet; the reference decides by the side of the
surface's normal the ray comes from, at every surface). This prints the relative L2 of
the stage's colour ("TechniqueColor") against the reference renderer's camera paths
("SpecularColor", 256 per pixel) with the eye inside the refractor, for the
screen-space, the distance-impostor and the combined (BOTH) camera views, and writes
reference | stage side by side (PNG, scaled by the reference's largest value) for a look.

  cd build && PYTHONPATH=lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \\
      ../scripts/camera-inside-glass.py [--scene NAME] [--eye X,Y,Z] [--focal X,Y,Z]
      [--up X,Y,Z] [--output DIR]

Under the pool's water (TestSpecularAppearance.CameraUnderTheWaterSheet):
  --scene pool --eye 0.5,0.4,0.8 --focal=-0.4,1.0,-0.6 --up 0,1,0
"""
import argparse
import os

import numpy as np
import OpenImageIO as oiio
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderWindow
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer

import vtkcaustics

SIZE = 128


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="ball-lens", help="built-in scene")
    parser.add_argument("--eye", default="0.35,3.4,0.25",
                        help="eye position, m (the ball: centre 0,3,0, radius 1)")
    parser.add_argument("--focal", default="0,0,0", help="focal point, m")
    parser.add_argument("--up", default="0,0,-1", help="view up")
    parser.add_argument("--output", default="camera-inside-glass")
    args = parser.parse_args()
    eye, focal, up = ([float(x) for x in a.split(",")] for a in (args.eye, args.focal, args.up))
    os.makedirs(args.output, exist_ok=True)

    renderer = vtkOpenGLRenderer()
    window = vtkRenderWindow()
    scene = vtkcaustics.vtkCausticsBuiltinScene()
    scene.SetSceneName(args.scene)
    if not scene.Populate(renderer):
        raise SystemExit(scene.GetLastError())
    camera = renderer.GetActiveCamera()
    camera.SetPosition(*eye)
    camera.SetFocalPoint(*focal)
    camera.SetViewUp(*up)
    camera.SetViewAngle(60)
    camera.SetClippingRange(0.01, 20)
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(SIZE, SIZE)
    window.AddRenderer(renderer)

    reference = vtkcaustics.vtkCausticsReferenceRenderer()
    reference.SetInputRenderer(renderer)
    reference.SetImageSize(SIZE, SIZE)
    reference.SetPhotonsPerLight(1000000)
    reference.SetSpecularSamples(256)
    if not reference.Update():
        raise SystemExit(reference.GetLastError())
    data = reference.GetOutput().GetPointData()
    truth = vtk_to_numpy(data.GetArray("SpecularColor")).reshape(SIZE, SIZE, -1)[:, :, :3]
    mask = vtk_to_numpy(data.GetArray("SpecularMask")).reshape(SIZE, SIZE) > 0

    for method, name in ((0, "screen-space"), (1, "impostors"), (2, "both")):
        technique = vtkcaustics.vtkCausticsTechniques.NewPass("screen-space")
        technique.SetLightBufferResolution(256)
        technique.SetCameraViewMethod(method)
        technique.KeepBuffersOn()
        renderer.SetPass(technique)
        window.Render()
        window.Render()
        image = vtkImageData()
        technique.ReadBuffer("TechniqueColor", image)
        renderer.SetPass(None)
        technique.ReleaseGraphicsResources(window)
        shown = vtk_to_numpy(image.GetPointData().GetArray(0)).reshape(SIZE, SIZE, -1)
        drawn = mask & (shown[:, :, 3] >= 0.5)
        difference = ((shown[:, :, :3] - truth)[drawn] ** 2).sum()
        norm = (truth[drawn] ** 2).sum()
        print(f"{name} view: {int(drawn.sum())} specular pixels, relative L2 "
              f"{100.0 * np.sqrt(difference / norm):.1f} %")
        pair = np.concatenate([truth, shown[:, :, :3]], axis=1)[::-1]
        pair = np.clip(pair / max(float(truth.max()), 1e-12), 0.0, 1.0)
        path = os.path.join(args.output, f"{name}.png")
        out = oiio.ImageOutput.create(path)
        out.open(path, oiio.ImageSpec(2 * SIZE, SIZE, 3, oiio.UINT8))
        out.write_image((pair * 255).astype(np.uint8))
        out.close()
    print(f"wrote reference | stage images to {args.output}/")


if __name__ == "__main__":
    main()
