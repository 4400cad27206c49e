#!/usr/bin/env python3
"""Writes ball-lens.gltf, the plugin test's scene: the built-in "ball-lens" scene
(vtkCausticsBuiltinScene) as glTF 2.0. A 12 x 12 floor at y = 0 (mesh "floor")
and a glass ball of radius 1 centred at y = 3 (mesh "glass ball", 48 x 24 faces,
KHR_materials_transmission and KHR_materials_ior 1.5), lit by a directional light
pointing down (KHR_lights_punctual). Buffers are embedded, so the file stands alone.

    python3 make-ball-lens-gltf.py [OUTPUT]
"""
import base64
import json
import math
import struct
import sys


def floor_mesh():
    positions = [(-6, 0, -6), (6, 0, -6), (6, 0, 6), (-6, 0, 6)]
    normals = [(0, 1, 0)] * 4
    indices = [0, 2, 1, 0, 3, 2]  # counter-clockwise seen from above
    return positions, normals, indices


def sphere_mesh(center, radius, slices=48, stacks=24):
    positions, normals, indices = [], [], []
    for i in range(stacks + 1):
        theta = math.pi * i / stacks
        for j in range(slices + 1):
            phi = 2 * math.pi * j / slices
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            normals.append(n)
            positions.append(tuple(c + radius * d for c, d in zip(center, n)))
    for i in range(stacks):
        for j in range(slices):
            a = i * (slices + 1) + j
            b = a + slices + 1
            if i > 0:
                indices += [a, a + 1, b]
            if i < stacks - 1:
                indices += [a + 1, b + 1, b]
    return positions, normals, indices


def main():
    output = sys.argv[1] if len(sys.argv) > 1 else "ball-lens.gltf"
    blob = bytearray()
    views, accessors, meshes = [], [], []

    def add_view(data, target):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data),
                      "target": target})
        blob.extend(data)
        return len(views) - 1

    def add_vec3(values):
        data = b"".join(struct.pack("<3f", *v) for v in values)
        accessor = {"bufferView": add_view(data, 34962), "componentType": 5126,
                    "count": len(values), "type": "VEC3",
                    "min": [min(v[k] for v in values) for k in range(3)],
                    "max": [max(v[k] for v in values) for k in range(3)]}
        accessors.append(accessor)
        return len(accessors) - 1

    def add_indices(values):
        data = struct.pack("<%dI" % len(values), *values)
        accessors.append({"bufferView": add_view(data, 34963), "componentType": 5125,
                          "count": len(values), "type": "SCALAR"})
        return len(accessors) - 1

    for name, (positions, normals, indices), material in (
            ("floor", floor_mesh(), 0),
            ("glass ball", sphere_mesh((0, 3, 0), 1.0), 1)):
        meshes.append({"name": name, "primitives": [{
            "attributes": {"POSITION": add_vec3(positions), "NORMAL": add_vec3(normals)},
            "indices": add_indices(indices), "material": material}]})

    # A node's -Z is a light's direction: rotate -90 degrees about X to point down.
    half = math.sqrt(0.5)
    document = {
        "asset": {"version": "2.0", "generator": "make-ball-lens-gltf.py"},
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior",
                           "KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "name": "sun", "intensity": 1.0, "color": [1, 1, 1]}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"name": "floor", "mesh": 0}, {"name": "glass ball", "mesh": 1},
                  {"name": "sun", "rotation": [-half, 0, 0, half],
                   "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "materials": [
            {"name": "diffuse grey", "pbrMetallicRoughness": {
                "baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
                "roughnessFactor": 1}},
            {"name": "glass", "pbrMetallicRoughness": {
                "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": 0},
             "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                            "KHR_materials_ior": {"ior": 1.5}}}],
        "meshes": meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(bytes(blob)).decode("ascii")}],
    }
    with open(output, "w") as stream:
        json.dump(document, stream, indent=1)
        stream.write("\n")


if __name__ == "__main__":
    main()
