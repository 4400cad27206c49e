#!/usr/bin/env python3
"""Per-frame cost of the shared camera-view stage, for each camera-view method.

Renders each built-in scene at 128² with the screen-space technique (256² photons) and
each SetCameraViewMethod (0 screen-space, 1 distance impostors, 2 both), and prints
the median and the least of GetGPUMilliseconds("refraction tracing") over 7 frames
after the first (the distance maps are made once, in the first).

  cd build && PYTHONPATH=lib/python3/dist-packages xvfb-run -n 91 /usr/bin/python3 \\
      ../scripts/camera-view-cost.py [ball-lens,ring,pool,bunny]
"""
import sys

import numpy as np
from vtkmodules.vtkRenderingCore import vtkRenderWindow
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer

import vtkcaustics

SIZE = 128
FRAMES = 7


def main():
    scenes = sys.argv[1] if len(sys.argv) > 1 else "ball-lens,ring,pool,bunny"
    for scene_name in scenes.split(","):
        for method in (0, 1, 2):
            renderer = vtkOpenGLRenderer()
            window = vtkRenderWindow()
            scene = vtkcaustics.vtkCausticsBuiltinScene()
            scene.SetSceneName(scene_name)
            if not scene.Populate(renderer):
                raise SystemExit(scene.GetLastError())
            window.SetOffScreenRendering(1)
            window.SetMultiSamples(0)
            window.SetSize(SIZE, SIZE)
            window.AddRenderer(renderer)
            technique = vtkcaustics.vtkCausticsTechniques.NewPass("screen-space")
            technique.SetLightBufferResolution(256)
            technique.SetCameraViewMethod(method)
            technique.GetTimings().SynchronousOn()
            renderer.SetPass(technique)
            window.Render()
            ms = []
            for _ in range(FRAMES):
                window.Render()
                ms.append(technique.GetTimings().GetGPUMilliseconds("refraction tracing"))
            print(f"{scene_name}, method {method}: median {np.median(ms):.1f} ms, "
                  f"least {min(ms):.1f} ms a frame")
            renderer.SetPass(None)
            technique.ReleaseGraphicsResources(window)


if __name__ == "__main__":
    main()
