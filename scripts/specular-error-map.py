#!/usr/bin/env python3
"""Where the camera-view stage's colour on glass and mirrors differs from the reference's.

The same comparison as TestSpecularAppearance (the pass's "TechniqueColor" against the
reference renderer's camera paths, "SpecularColor", on the specular pixels the stage
drew, 128² pixels, 256² photons, the built-in scenes' own cameras), split so that the
causes can be told apart:

- the reference's own noise: it is rendered twice with different seeds; the relative L2
  of the difference / √2 is its floor (what a perfect stage would still show), and
  sqrt(error² - floor²) the stage's bias;
- mirror pixels and glass pixels (the first surface: the reference's mask, the pass's
  opaque G-buffer role);
- pixels where some screen-space march left the view (the screen-space and the combined
  views differ there) and the others;
- missing light (stage below the reference) against extra light, and the mean ratio;
- with --split-caustic, pixels whose reference colour is mostly caustic light (more than
  half of it goes when the reference has no photons: the technique's caustic, seen through
  the glass or in the mirror) and the others.

  cd build && PYTHONPATH=lib/python3/dist-packages xvfb-run -n 91 /usr/bin/python3 \\
      ../scripts/specular-error-map.py [--scenes ball-lens,ring,pool,bunny]
      [--methods 1,2] [--technique screen-space,impostors] [--output DIR]

--technique: the photon technique(s) whose pass draws the camera view (default
screen-space), each compared with the same reference. The camera view shades a hit the
camera does not see from the distance impostors' map radiance plus the caustic store,
which the technique's photons fill.

Writes DIR/SCENE-METHOD.png (DIR/SCENE-TECHNIQUE-METHOD.png for a technique other than
screen-space): reference | stage | difference (red: extra, blue: missing),
scaled by the reference's 99th percentile.
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

SIZE = int(os.environ.get("SPECULAR_MAP_SIZE", "128"))
NAMES = {0: "screen-space", 1: "impostors", 2: "both"}
ROLE_REFLECTOR = 2


def array(image, name, components):
    data = vtk_to_numpy(image.GetPointData().GetArray(name))
    return data.reshape(SIZE, SIZE, -1)[:, :, :components]


def reference_color(renderer, seed, photons=1000000):
    reference = vtkcaustics.vtkCausticsReferenceRenderer()
    reference.SetInputRenderer(renderer)
    reference.SetImageSize(SIZE, SIZE)
    reference.SetPhotonsPerLight(photons)
    reference.SetSpecularSamples(256)
    reference.SetSeed(seed)
    if not reference.Update():
        raise SystemExit(reference.GetLastError())
    out = reference.GetOutput()
    return array(out, "SpecularColor", 3).astype(np.float64), \
        array(out, "SpecularMask", 1)[:, :, 0] > 0


def stage(renderer, window, method, name, store_radius=None, store_samples=None,
          store_coarse_samples=None, internal_reflections=None, exact_specular=None):
    technique = vtkcaustics.vtkCausticsTechniques.NewPass(name)
    if technique is None:
        raise SystemExit(f"unknown technique {name!r}")
    technique.SetLightBufferResolution(256)
    if store_radius is not None:
        technique.GetDistanceImpostors().SetCausticRadius(store_radius)
    if store_samples is not None:
        technique.GetDistanceImpostors().SetCausticSamples(store_samples)
    if store_coarse_samples is not None:
        technique.GetDistanceImpostors().SetCausticCoarseSamples(store_coarse_samples)
    technique.SetCameraViewMethod(method)
    if internal_reflections is not None:
        technique.GetScreenSpaceRefraction().SetInternalReflections(internal_reflections == "on")
    if exact_specular is not None:
        technique.GetScreenSpaceRefraction().SetExactSpecularGeometry(
            {"off": 0, "on": 1, "auto": 2}[exact_specular])
    technique.KeepBuffersOn()
    renderer.SetPass(technique)
    window.Render()
    window.Render()
    buffers = {}
    for name in ("TechniqueColor", "Normal"):
        image = vtkImageData()
        technique.ReadBuffer(name, image)
        buffers[name] = vtk_to_numpy(image.GetPointData().GetArray(0)).reshape(
            SIZE, SIZE, -1).astype(np.float64)
    renderer.SetPass(None)
    technique.ReleaseGraphicsResources(window)
    return buffers


def rel(a, b, where):
    norm = (b[where] ** 2).sum()
    return np.sqrt(((a - b)[where] ** 2).sum() / norm) if norm > 0 else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", default="ball-lens,ring,pool,bunny")
    parser.add_argument("--methods", default="1,2")
    parser.add_argument("--technique", default="screen-space",
                        help="comma-separated photon techniques (vtkCausticsTechniques names)")
    parser.add_argument("--store-radius", type=int, default=None,
                        help="the caustic store's read window (texels; default: the class's)")
    parser.add_argument("--store-samples", type=int, default=None,
                        help="deposits the store's read window grows to hold (default: the class's)")
    parser.add_argument("--store-coarse-samples", type=int, default=None,
                        help="deposits the store's coarse window grows to hold (default: the class's)")
    parser.add_argument("--camera", default=None,
                        help="EYE:FOCAL, e.g. 2.5,2,2.5:0,0.2,0 (view up +y): a framing "
                             "other than the scene's own")
    parser.add_argument("--view-angle", type=float, default=None,
                        help="with --camera: the vertical field of view in degrees "
                             "(default: the scene's)")
    parser.add_argument("--internal-reflections", choices=("on", "off"), default=None,
                        help="follow the Fresnel-reflected branch inside glass or not "
                             "(the stage's InternalReflections; default: the class's, on)")
    parser.add_argument("--exact-specular", choices=("on", "off", "auto"), default=None,
                        help="trace the glass and mirror triangles themselves or find them in "
                             "the layers and maps (the stage's ExactSpecularGeometry; default: "
                             "the class's, auto: where one is not a convex solid)")
    parser.add_argument("--split-caustic", action="store_true",
                        help="also split the error between the pixels whose reference colour "
                             "is mostly caustic light (the technique's photons, seen through the "
                             "glass or in the mirror) and the others; renders the reference once "
                             "more with one photon")
    parser.add_argument("--no-noise", action="store_true",
                        help="render the reference once (no noise floor): half the time")
    parser.add_argument("--output", default="specular-error-map")
    parser.add_argument("--arrays", action="store_true",
                        help="also write SCENE-METHOD.npz (reference, stage, masks)")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)
    methods = [int(m) for m in args.methods.split(",")]
    for scene_name in args.scenes.split(","):
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
        if args.camera:
            eye, focal = ([float(v) for v in part.split(",")] for part in args.camera.split(":"))
            camera = renderer.GetActiveCamera()
            camera.SetPosition(*eye)
            camera.SetFocalPoint(*focal)
            camera.SetViewUp(0.0, 1.0, 0.0)
            if args.view_angle:
                camera.SetViewAngle(args.view_angle)
            renderer.ResetCameraClippingRange()
        truth, mask = reference_color(renderer, 1)
        # The pixels whose light is mostly caustic: the reference without its photons
        # (one) keeps the direct light alone.
        caustic_share = None
        if args.split_caustic:
            direct, _ = reference_color(renderer, 1, photons=1)
            caustic_share = ((truth - direct).sum(axis=-1) /
                             np.maximum(truth.sum(axis=-1), 1e-30))
        if args.no_noise:
            other, floor = truth, 0.0  # the bias below is then the error itself
        else:
            other, _ = reference_color(renderer, 2)
            floor = rel(other, truth, mask) / np.sqrt(2.0)
            print(f"{scene_name}: reference noise floor (seeds 1, 2; /sqrt 2) {100 * floor:.1f} %")
        for name in args.technique.split(","):
            views = {m: stage(renderer, window, m, name, args.store_radius, args.store_samples,
                              args.store_coarse_samples, args.internal_reflections,
                              args.exact_specular) for m in sorted(set(methods + [0, 2]))}
            # Pixels where a march left the view: there the combined view took the impostors.
            left = np.abs(views[0]["TechniqueColor"][:, :, :3] -
                          views[2]["TechniqueColor"][:, :, :3]).max(axis=-1) > 1e-6
            for method in methods:
                color = views[method]["TechniqueColor"]
                shown = color[:, :, :3]
                drawn = mask & (color[:, :, 3] >= 0.5)
                mirror = np.rint(views[method]["Normal"][:, :, 3]) == ROLE_REFLECTOR
                error = rel(shown, truth, drawn)
                bias = np.sqrt(max(error ** 2 - floor ** 2, 0.0))
                squared = ((shown - truth) ** 2).sum(axis=-1)
                total = squared[drawn].sum()
                missing = (np.minimum(shown - truth, 0.0) ** 2).sum(axis=-1)[drawn].sum() / total
                ratio = shown[drawn].sum() / truth[drawn].sum()
                print(f"  {name}, {NAMES[method]} view: {int(drawn.sum())} pixels, relative L2 "
                      f"{100 * error:.1f} % (bias without the reference's noise {100 * bias:.1f} %), "
                      f"mean ratio {ratio:.3f}, {100 * missing:.0f} % of the squared error missing light")
                parts = [("mirror", drawn & mirror), ("glass", drawn & ~mirror),
                         ("a march left the view", drawn & left),
                         ("marches stayed in the view", drawn & ~left)]
                if caustic_share is not None:
                    parts += [("mostly caustic light", drawn & (caustic_share > 0.5)),
                              ("mostly direct light", drawn & ~(caustic_share > 0.5))]
                for label, part in parts:
                    if part.sum() == 0:
                        continue
                    share = squared[part].sum() / total
                    r = shown[part].sum() / max(truth[part].sum(), 1e-30)
                    print(f"    {label}: {int(part.sum())} px, {100 * share:.0f} % of the squared "
                          f"error, own relative L2 {100 * rel(shown, truth, part):.1f} %, "
                          f"mean ratio {r:.3f}")
                top = max(float(np.percentile(truth[drawn], 99)), 1e-12)
                difference = np.where(drawn[:, :, None], shown - truth, 0.0).mean(axis=-1)
                red = np.clip(difference / (top / 3), 0.0, 1.0)
                blue = np.clip(-difference / (top / 3), 0.0, 1.0)
                diff = np.stack([red, np.zeros_like(red), blue], axis=-1)
                mask3 = drawn[:, :, None]
                pair = np.concatenate([np.clip(np.where(mask3, truth, 0) / top, 0, 1),
                                       np.clip(np.where(mask3, shown, 0) / top, 0, 1), diff],
                                      axis=1)[::-1]
                stem = scene_name if name == "screen-space" else f"{scene_name}-{name}"
                path = os.path.join(args.output, f"{stem}-{NAMES[method]}.png")
                out = oiio.ImageOutput.create(path)
                out.open(path, oiio.ImageSpec(3 * SIZE, SIZE, 3, oiio.UINT8))
                out.write_image(np.ascontiguousarray((pair * 255).astype(np.uint8)))
                out.close()
                if args.arrays:
                    np.savez(os.path.join(args.output, f"{stem}-{NAMES[method]}.npz"),
                             truth=truth, other=other, shown=shown, drawn=drawn, left=left,
                             mirror=mirror)
    print(f"wrote reference | stage | difference images to {args.output}/")


if __name__ == "__main__":
    main()
