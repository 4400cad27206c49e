#!/usr/bin/env python3
"""The noise of one of the reference's volume arrays on a built-in scene, in one run.

Renders the scene's reference (vtkCausticsReferenceRenderer) with seeds 1 and 2 and
prints the relative L2 between them and its share per seed (/ sqrt 2): the floor under
which no GPU result can be measured against one reference.

- The airlight (default), as TestAirlight does (128^2, 1000 photons;
  TestAirlight.MediaScenesMatchReference, docs/airlight.md):
    PYTHONPATH=build/lib/python3/dist-packages CAUSTICS_REFERENCE_CACHE=build/reference-cache \\
        /usr/bin/python3 scripts/reference-noise.py smoke-lens
- The volume caustic, as TestVolumeLines does (200 000 volume photons on smoke-lens,
  1 000 000 on underwater, at 128^2 or 256^2; docs/technique-volume-caustics.md):
    ... scripts/reference-noise.py underwater --array VolumeCausticRadiance \\
        --size 256 --volume-photons 1000000
  This is the raw per-pixel noise; at a technique's resolution (its blur) it is far
  lower: scripts/volume-error-map.py prints both.
"""
import argparse
import math
import sys

from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer
from vtkmodules.util.numpy_support import vtk_to_numpy

import vtkcaustics  # noqa: F401 (loads VTK's OpenGL modules first)
from vtkcaustics.vtkIOCaustics import vtkCausticsBuiltinScene
from vtkcaustics.vtkCausticsReference import vtkCausticsReferenceRenderer


def render(renderer, args, seed):
    reference = vtkCausticsReferenceRenderer()
    reference.SetInputRenderer(renderer)
    reference.SetImageSize(args.size, args.size)
    reference.SetPhotonsPerLight(args.photons)
    reference.SetVolumePhotonsPerLight(args.volume_photons)
    reference.SetSeed(seed)
    if not reference.Update():
        sys.exit(reference.GetLastError())
    array = reference.GetOutput().GetPointData().GetArray(args.array)
    if array is None:
        sys.exit(f"the reference has no array {args.array}")
    return vtk_to_numpy(array).astype(float)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?", default="smoke-lens", help="built-in scene")
    parser.add_argument("--array", default="AirlightRadiance",
                        help="AirlightRadiance, VolumeCausticRadiance, CausticIrradiance ...")
    parser.add_argument("--size", type=int, default=128, help="image side, pixels")
    parser.add_argument("--photons", type=int, default=1000, help="surface photons per light")
    parser.add_argument("--volume-photons", type=int, default=1000,
                        help="volume (beam) photons per light")
    args = parser.parse_args()
    renderer = vtkOpenGLRenderer()
    scene = vtkCausticsBuiltinScene()
    scene.SetSceneName(args.scene)
    if not scene.Populate(renderer):
        sys.exit(scene.GetLastError())
    a, b = render(renderer, args, 1), render(renderer, args, 2)
    norm = (b ** 2).sum()
    if norm <= 0.0:
        print(f"{args.scene}: the reference's {args.array} is 0 everywhere")
        return
    l2 = math.sqrt(((a - b) ** 2).sum() / norm)
    print(f"{args.scene}, {args.array} at {args.size}^2: reference seeds 1 and 2 differ by a "
          f"relative L2 of {l2:.4f}; one seed's noise is about {l2 / math.sqrt(2):.4f}")


if __name__ == "__main__":
    main()
