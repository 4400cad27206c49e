#!/usr/bin/env python3
"""The camera-view splats along a receiver's end and along the image's border.

Writes two glTF scenes that the tests do not have, each lit evenly through flat glass
so that the exact irradiance is uniform on every receiver, renders them with
caustics-render (each technique, and the CPU reference), and prints:

- corner: a 2 m floor with a back wall and a left wall (1 m tall), under a 10 cm glass
  slab, sun along (-0.35, -1, -0.45), camera at (0.6, 1, 2.2) looking at
  (-0.3, 0.2, -0.5); the back wall reaches past the image's top border, the floor past
  its bottom and right borders. Printed: relative L2 and flux against the reference,
  the floor's and the walls' flux ratios, the mean ratio of the outermost eight rows
  (top, bottom) and columns (right) to the reference, and the profile across the back
  wall's foot (k < 0: wall rows above the foot, k >= 0: floor rows).
- sheet: a 2 m floor under a 6 m water sheet 1 m up (n = 1.33), sun along
  (-0.3, -1, -0.2), camera at (4, 1.6, 0.3) looking at the origin, beside the sheet:
  relative L2 and flux, and the ratio on the floor's last rows at its near and far
  edges.

    xvfb-run -a /usr/bin/python3 scripts/kernel-ends.py [--render build/bin/caustics-render]
        [--techniques screen-space,cascaded,impostors] [--size 256] [--photons 256]
        [--reference-photons 4e6] [--output DIR]

Reads EXR with OpenImageIO's Python module (Debian: python3-openimageio).
docs/accuracy.md ("Kernels at a receiver's end", "Camera independence") quotes it.
"""
import argparse
import base64
import importlib.util
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("error_map", os.path.join(HERE, "error-map.py"))
error_map = importlib.util.module_from_spec(spec)
spec.loader.exec_module(error_map)  # its EXR reader: reference_layers, Layers


def grid_quad(origin, u, v, normal, divisions):
    """A quad origin + s u + t v split into divisions^2 cells, wound to face `normal`."""
    origin, u, v, normal = map(np.asarray, (origin, u, v, normal))
    vertices = [origin + u * i / divisions + v * j / divisions
                for j in range(divisions + 1) for i in range(divisions + 1)]
    indices = []
    for j in range(divisions):
        for i in range(divisions):
            a = j * (divisions + 1) + i
            b, c, d = a + 1, a + divisions + 1, a + divisions + 2
            for tri in ((a, b, d), (a, d, c)):
                p0, p1, p2 = (vertices[k] for k in tri)
                if np.dot(np.cross(p1 - p0, p2 - p0), normal) < 0:
                    tri = (tri[0], tri[2], tri[1])
                indices.extend(tri)
    return (np.array(vertices, np.float32), np.tile(np.asarray(normal, np.float32),
            (len(vertices), 1)), np.array(indices, np.uint32))


def box(low, high):
    """A closed box as six two-by-two quads, outward normals."""
    low, high = np.asarray(low, float), np.asarray(high, float)
    d = high - low
    faces = [
        ((low[0], high[1], low[2]), (d[0], 0, 0), (0, 0, d[2]), (0, 1, 0)),
        (tuple(low), (d[0], 0, 0), (0, 0, d[2]), (0, -1, 0)),
        ((low[0], low[1], high[2]), (d[0], 0, 0), (0, d[1], 0), (0, 0, 1)),
        (tuple(low), (d[0], 0, 0), (0, d[1], 0), (0, 0, -1)),
        ((high[0], low[1], low[2]), (0, 0, d[2]), (0, d[1], 0), (1, 0, 0)),
        (tuple(low), (0, 0, d[2]), (0, d[1], 0), (-1, 0, 0)),
    ]
    parts = [grid_quad(o, u, v, n, 2) for o, u, v, n in faces]
    offset, indices = 0, []
    for vertices, _, faces_indices in parts:
        indices.append(faces_indices + offset)
        offset += len(vertices)
    return (np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]),
            np.concatenate(indices).astype(np.uint32))


def write_gltf(path, meshes, sun):
    """meshes: (name, (vertices, normals, indices), 'diffuse' | 'glass'); sun: direction
    the light travels (1 W/m^2)."""
    data, views, accessors, gltf_meshes, nodes = b"", [], [], [], []
    for name, arrays, material in meshes:
        for array, kind, target in zip(arrays, ("VEC3", "VEC3", "SCALAR"), (34962, 34962, 34963)):
            raw = array.tobytes()
            views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(raw),
                          "target": target})
            data += raw + b"\0" * ((4 - len(raw) % 4) % 4)
            accessor = {"bufferView": len(views) - 1, "count": len(array), "type": kind,
                        "componentType": 5126 if kind == "VEC3" else 5125}
            if kind == "VEC3":
                accessor["min"] = array.min(0).tolist()
                accessor["max"] = array.max(0).tolist()
            accessors.append(accessor)
        first = len(accessors) - 3
        gltf_meshes.append({"name": name, "primitives": [{
            "attributes": {"POSITION": first, "NORMAL": first + 1}, "indices": first + 2,
            "material": 0 if material == "diffuse" else 1}]})
        nodes.append({"name": name, "mesh": len(gltf_meshes) - 1})
    # The light looks along its node's -z: the rotation taking -z to `sun`.
    d = np.asarray(sun, float) / np.linalg.norm(sun)
    z = np.array([0.0, 0.0, -1.0])
    axis = np.cross(z, d)
    angle = math.atan2(np.linalg.norm(axis), np.dot(z, d))
    axis /= np.linalg.norm(axis)
    rotation = [*(axis * math.sin(angle / 2)), math.cos(angle / 2)]
    nodes.append({"name": "sun", "rotation": rotation,
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    gltf = {
        "asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": gltf_meshes,
        "materials": [
            {"name": "diffuse", "pbrMetallicRoughness": {
                "baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 1}},
            {"name": "glass", "pbrMetallicRoughness": {
                "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": 0},
             "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                            "KHR_materials_ior": {"ior": 1.5}}}],
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior",
                           "KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "intensity": 1.0, "color": [1, 1, 1]}]}},
        "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(data).decode()}]}
    with open(path, "w") as f:
        json.dump(gltf, f)


def corner_scene(path):
    write_gltf(path, [
        ("floor", grid_quad((-1, 0, 1), (2, 0, 0), (0, 0, -2), (0, 1, 0), 8), "diffuse"),
        ("back wall", grid_quad((-1, 0, -1), (2, 0, 0), (0, 1, 0), (0, 0, 1), 8), "diffuse"),
        ("left wall", grid_quad((-1, 0, 1), (0, 0, -2), (0, 1, 0), (1, 0, 0), 8), "diffuse"),
        ("slab", box((-2, 1.2, -2), (2, 1.3, 2)), "glass"),
    ], (-0.35, -1.0, -0.45))


def sheet_scene(path):
    water = grid_quad((-3, 1, 3), (6, 0, 0), (0, 0, -6), (0, 1, 0), 32)
    write_gltf(path, [
        ("floor", grid_quad((-1, 0, 1), (2, 0, 0), (0, 0, -2), (0, 1, 0), 8), "diffuse"),
        ("sheet", water, "glass"),
    ], (-0.3, -1.0, -0.2))
    # The sheet's material is the glass's n = 1.5 in write_gltf; water is 1.33.
    with open(path) as f:
        gltf = json.load(f)
    gltf["materials"].append({"name": "water", "pbrMetallicRoughness": {
        "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": 0},
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                       "KHR_materials_ior": {"ior": 1.33}}})
    gltf["meshes"][1]["primitives"][0]["material"] = 2
    with open(path, "w") as f:
        json.dump(gltf, f)


CAMERAS = {
    "corner": ("0.6,1.0,2.2", "-0.3,0.2,-0.5"),
    "sheet": ("4,1.6,0.3", "0,0,0"),
}


def render(options, scene_path, scene, technique, prefix):
    position, focal = CAMERAS[scene]
    command = [options.render, scene_path, "--camera-index", "-1", "--camera-position", position,
               "--camera-focal", focal, "--size", str(options.size), "--output", prefix]
    if technique == "reference":
        command += ["--technique", "none", "--reference", "--reference-photons",
                    str(options.reference_photons)]
    else:
        command += ["--technique", technique, "--photons", str(options.photons)]
    out = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if out.returncode != 0:
        sys.exit(f"{' '.join(command)} failed ({out.returncode}):\n{out.stdout[-2000:]}")
    return prefix + ("-reference.exr" if technique == "reference" else ".exr")


def compare(reference, mask, image):
    on = mask
    difference = (image - reference)[on]
    l2 = math.sqrt(float((difference ** 2).sum()) / max(float((reference[on] ** 2).sum()), 1e-30))
    flux = float(image[on].sum()) / max(float(reference[on].sum()), 1e-30)
    return l2, flux


def ratio(image, reference, rows, cols):
    return float(image[rows, cols].sum()) / max(float(reference[rows, cols].sum()), 1e-30)


def corner_figures(reference, image):
    r, im = reference.mean(axis=2), image.mean(axis=2)
    size = r.shape[0]
    floor, walls = r > 0.6, (r > 0.2) & (r < 0.5)
    lines = ["floor %.4f, walls %.4f" % (im[floor].sum() / r[floor].sum(),
                                          im[walls].sum() / r[walls].sum())]
    span = slice(size * 100 // 256, size * 250 // 256)
    lines.append("outermost rows, top: " + " ".join(
        "%.2f" % ratio(im, r, y, span) for y in range(8)))
    lines.append("outermost rows, bottom: " + " ".join(
        "%.2f" % ratio(im, r, y, span) for y in range(size - 1, size - 9, -1)))
    rows = slice(size * 170 // 256, size * 250 // 256)
    lines.append("outermost columns, right: " + " ".join(
        "%.2f" % ratio(im, r, rows, x) for x in range(size - 1, size - 9, -1)))
    profile = {}
    for x in range(size * 120 // 256, size * 240 // 256):
        foot = int(np.argmax(r[:, x] > 0.6))  # the back wall's foot: first floor row
        for k in range(-6, 7):
            profile.setdefault(k, []).append(im[foot + k, x] / max(r[foot + k, x], 1e-30))
    lines.append("across the back wall's foot (k < 0 wall, k >= 0 floor): " + " ".join(
        "%+d:%.2f" % (k, np.mean(v)) for k, v in sorted(profile.items())))
    return lines


def sheet_figures(reference, image):
    r, im = reference.mean(axis=2), image.mean(axis=2)
    size = r.shape[0]
    near, far = {}, {}
    for x in range(size * 60 // 256, size * 200 // 256):
        rows = np.where(r[:, x] > 0.5)[0]
        if len(rows) == 0:
            continue
        for k in range(4):
            near.setdefault(k, []).append(im[rows.max() - k, x] / r[rows.max() - k, x])
            far.setdefault(k, []).append(im[rows.min() + k, x] / r[rows.min() + k, x])
    return ["floor's near edge, last rows inward: " + " ".join(
                "%.3f" % np.mean(near[k]) for k in sorted(near)),
            "floor's far edge, last rows inward: " + " ".join(
                "%.3f" % np.mean(far[k]) for k in sorted(far))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--render", default="build/bin/caustics-render")
    parser.add_argument("--techniques", default="screen-space,cascaded,impostors")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--photons", type=int, default=256)
    parser.add_argument("--reference-photons", type=float, default=4e6)
    parser.add_argument("--output", default=None, help="keep the scenes and images here")
    options = parser.parse_args()
    directory = options.output or tempfile.mkdtemp(prefix="kernel-ends-")
    os.makedirs(directory, exist_ok=True)
    for scene, make, figures in (("corner", corner_scene, corner_figures),
                                 ("sheet", sheet_scene, sheet_figures)):
        path = os.path.join(directory, scene + ".gltf")
        make(path)
        reference, mask, _ = error_map.reference_layers(
            render(options, path, scene, "reference", os.path.join(directory, scene)))
        print("%s (reference %g photons)" % (scene, options.reference_photons))
        for technique in options.techniques.split(","):
            image = error_map.Layers(render(
                options, path, scene, technique,
                os.path.join(directory, scene + "-" + technique))).rgb("caustic")
            l2, flux = compare(reference, mask, image)
            print("  %s: relative L2 %.4f, flux %.4f" % (technique, l2, flux))
            for line in figures(reference, image):
                print("    " + line)
        sys.stdout.flush()


if __name__ == "__main__":
    main()
