#!/usr/bin/env python3
"""The noise of the reference's AirlightRadiance on a built-in scene, in one run.

Renders the scene's reference (vtkCausticsReferenceRenderer, as TestAirlight does:
128^2, 1000 photons) with seeds 1 and 2 and prints the relative L2 between them and
its share per seed (/ sqrt 2): the floor under which no GPU airlight can be measured
against one reference (TestAirlight.MediaScenesMatchReference, docs/airlight.md).

  PYTHONPATH=build/lib/python3/dist-packages CAUSTICS_REFERENCE_CACHE=build/reference-cache \\
      /usr/bin/python3 scripts/airlight-reference-noise.py [underwater]
"""
import math
import sys

from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer
from vtkmodules.util.numpy_support import vtk_to_numpy

import vtkcaustics  # noqa: F401 (loads VTK's OpenGL modules first)
from vtkcaustics.vtkIOCaustics import vtkCausticsBuiltinScene
from vtkcaustics.vtkCausticsReference import vtkCausticsReferenceRenderer


def airlight(renderer, seed):
    reference = vtkCausticsReferenceRenderer()
    reference.SetInputRenderer(renderer)
    reference.SetImageSize(128, 128)
    reference.SetPhotonsPerLight(1000)
    reference.SetVolumePhotonsPerLight(1000)
    reference.SetSeed(seed)
    if not reference.Update():
        sys.exit(reference.GetLastError())
    array = reference.GetOutput().GetPointData().GetArray("AirlightRadiance")
    return vtk_to_numpy(array).astype(float)


def main():
    name = sys.argv[1] if len(sys.argv) > 1 else "underwater"
    renderer = vtkOpenGLRenderer()
    scene = vtkCausticsBuiltinScene()
    scene.SetSceneName(name)
    if not scene.Populate(renderer):
        sys.exit(scene.GetLastError())
    a, b = airlight(renderer, 1), airlight(renderer, 2)
    norm = (b ** 2).sum()
    if norm <= 0.0:
        print(f"{name}: the reference's airlight is 0 everywhere")
        return
    l2 = math.sqrt(((a - b) ** 2).sum() / norm)
    print(f"{name}: reference seeds 1 and 2 differ by a relative L2 of {l2:.4f}; "
          f"one seed's noise is about {l2 / math.sqrt(2):.4f}")


if __name__ == "__main__":
    main()
