#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets: Testing/Fuzz/corpus/<target>/.

Valid minimal files of every format the readers take, a small cut of
Data/bunny.ply, and the known-bad cases that Testing/Cxx/TestGLTFImporter.cxx
and TestMeshReader.cxx already cover, each a few hundred bytes to a few KB. The
output is committed, so that the corpus replay (ctest FuzzCorpusReplay) needs no
Python; rerun this after changing it:  python3 Testing/Fuzz/make-seeds.py
"""
import base64
import copy
import json
import math
import os
import shutil
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")
DATA = os.path.join(HERE, "..", "..", "Data")


def write(target, name, content):
    folder = os.path.join(CORPUS, target)
    os.makedirs(folder, exist_ok=True)
    if isinstance(content, str):
        content = content.encode()
    with open(os.path.join(folder, name), "wb") as f:
        f.write(content)


# --- glTF ---------------------------------------------------------------------------------

def scene_buffer(bad_index=0):
    """A 4 m quad (4 vertices, 6 uint16 indices) and a unit triangle, as in TestGLTFImporter."""
    quad = struct.pack("<12f", -2, 0, 2, 2, 0, 2, 2, 0, -2, -2, 0, -2)
    indices = struct.pack("<6H", 0, 1, 2, 0, 2, bad_index or 3)
    triangle = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    return quad + indices + triangle


def data_uri(data, mime="application/octet-stream"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())


def rotation(ax, ay, az, degrees):
    half = math.radians(degrees) / 2
    s = math.sin(half)
    return [ax * s, ay * s, az * s, math.cos(half)]


def minimal_document():
    data = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    return {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(data), "uri": data_uri(data)}],
        "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }


def scene_document():
    """TestGLTFImporter's SceneDocument(): materials, lights, cameras under transformed parents."""
    data = scene_buffer()
    material = lambda name, color, metallic, roughness: {
        "name": name, "pbrMetallicRoughness": {
            "baseColorFactor": color, "metallicFactor": metallic, "roughnessFactor": roughness}}
    glass = material("glass", [1, 1, 1, 1], 0.0, 0.0)
    glass["extensions"] = {
        "KHR_materials_ior": {"ior": 1.33},
        "KHR_materials_transmission": {"transmissionFactor": 1.0},
        "KHR_materials_volume": {"attenuationDistance": 2.0, "attenuationColor": [0.5, 1, 1]}}
    return {
        "asset": {"version": "2.0", "generator": "make-seeds.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_ior",
                           "KHR_materials_transmission", "KHR_materials_volume"],
        "buffers": [{"byteLength": len(data), "uri": data_uri(data)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 12},
                        {"buffer": 0, "byteOffset": 60, "byteLength": 36}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-2, 0, -2], "max": [2, 0, 2]},
            {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]}],
        "materials": [material("white", [0.8, 0.8, 0.8, 1], 0.0, 1.0), glass,
                      material("polished", [0.95, 0.64, 0.54, 1], 1.0, 0.1),
                      material("rough", [0.95, 0.64, 0.54, 1], 1.0, 0.6)],
        "meshes": [
            {"name": "floor", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                                              "material": 0}]},
            {"name": "prism", "primitives": [{"attributes": {"POSITION": 2}, "material": 1}]},
            {"name": "metals", "primitives": [{"attributes": {"POSITION": 2}, "material": 2},
                                              {"attributes": {"POSITION": 2}, "material": 3}]},
            {"name": "plain", "primitives": [{"attributes": {"POSITION": 2}}]}],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "intensity": 3.0},
            {"type": "spot", "intensity": 5.0, "color": [1, 0.5, 0.25], "range": 10.0,
             "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
            {"type": "directional", "intensity": 2.0}]}},
        "cameras": [
            {"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5,
                                                    "znear": 0.1, "zfar": 50.0}},
            {"type": "orthographic", "orthographic": {"xmag": 3.0, "ymag": 2.0,
                                                      "znear": 0.01, "zfar": 20.0}}],
        "nodes": [
            {"name": "floor", "mesh": 0},
            {"name": "glass", "mesh": 1, "translation": [0, 1, 0]},
            {"mesh": 2},
            {"name": "plain node", "mesh": 3},
            {"name": "rig", "translation": [0, 2, 0], "rotation": rotation(0, 0, 1, 90),
             "scale": [2, 2, 2], "children": [5, 6]},
            {"name": "bulb", "translation": [1, 0, 0],
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "spot", "translation": [0, 1, 0], "rotation": rotation(1, 0, 0, -90),
             "extensions": {"KHR_lights_punctual": {"light": 1}}},
            {"name": "sky", "rotation": rotation(0, 1, 0, 90), "translation": [5, 5, 5],
             "children": [8]},
            {"name": "sun", "rotation": rotation(1, 0, 0, -60),
             "extensions": {"KHR_lights_punctual": {"light": 2}}},
            {"name": "eye", "translation": [0, 1, 5], "camera": 0},
            {"name": "dolly", "translation": [0, 1, 0], "children": [9]},
            {"name": "top", "translation": [0, 10, 0], "rotation": rotation(1, 0, 0, -90),
             "camera": 1}],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3, 4, 7, 10, 11]}],
    }


def modes_document():
    """Strips, fans, lines and points, uint8 and uint32 indices, a strided view, normals."""
    doc = minimal_document()
    positions = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0)
    normals = struct.pack("<12f", 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1)
    strided = b"".join(positions[12 * i:12 * i + 12] + normals[12 * i:12 * i + 12]
                       for i in range(4))
    u8 = struct.pack("<4B", 0, 1, 2, 3)
    u32 = struct.pack("<4I", 0, 1, 2, 3)
    data = strided + u8 + u32
    doc["buffers"] = [{"byteLength": len(data), "uri": data_uri(data)}]
    doc["bufferViews"] = [{"buffer": 0, "byteLength": 96, "byteStride": 24},
                          {"buffer": 0, "byteOffset": 96, "byteLength": 4},
                          {"buffer": 0, "byteOffset": 100, "byteLength": 16}]
    doc["accessors"] = [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 1, "componentType": 5121, "count": 4, "type": "SCALAR"},
        {"bufferView": 2, "componentType": 5125, "count": 4, "type": "SCALAR"}]
    doc["meshes"] = [{"primitives": [
        {"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "mode": mode}
        for mode in (0, 1, 2, 3, 5, 6)] + [
        {"attributes": {"POSITION": 0}, "indices": 3, "mode": 4}]}]
    return doc


def animated_document():
    """One node translated by a linear animation (two keyframes)."""
    doc = minimal_document()
    triangle = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    times = struct.pack("<2f", 0, 1)
    moves = struct.pack("<6f", 0, 0, 0, 1, 0, 0)
    data = triangle + times + moves
    doc["buffers"] = [{"byteLength": len(data), "uri": data_uri(data)}]
    doc["bufferViews"] = [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36,
                          "byteLength": 8}, {"buffer": 0, "byteOffset": 44, "byteLength": 24}]
    doc["accessors"] += [
        {"bufferView": 1, "componentType": 5126, "count": 2, "type": "SCALAR",
         "min": [0], "max": [1]},
        {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3"}]
    doc["animations"] = [{"samplers": [{"input": 1, "output": 2, "interpolation": "LINEAR"}],
                          "channels": [{"sampler": 0,
                                        "target": {"node": 0, "path": "translation"}}]}]
    return doc


def chain_document(depth):
    """A triangle at the end of a chain of `depth` nodes, each the only child of the previous."""
    doc = minimal_document()
    doc["nodes"] = [{"children": [i + 1]} for i in range(depth - 1)] + [{"mesh": 0}]
    return doc


def gltf_variants():
    """The bad files of TestGLTFImporter, by name: (document or text)."""
    v = {}

    def variant(name, change):
        doc = scene_document()
        change(doc)
        v[name] = doc

    L = lambda doc: doc["extensions"]["KHR_lights_punctual"]["lights"]
    variant("bad-material-index", lambda d: d["meshes"][1]["primitives"][0].update(material=9))
    variant("bad-mesh-index", lambda d: d["nodes"][0].update(mesh=7))
    variant("bad-scene-node", lambda d: d["scenes"][0]["nodes"].append(42))
    variant("bad-child", lambda d: d["nodes"][4]["children"].append(-1))
    variant("bad-light", lambda d: d["nodes"][5]["extensions"]["KHR_lights_punctual"]
            .update(light=3))
    variant("bad-view", lambda d: d["accessors"][2].update(bufferView=3))
    variant("bad-vertex-index", lambda d: d["buffers"][0].update(uri=data_uri(scene_buffer(9))))
    variant("cycle", lambda d: d["nodes"][6].update(children=[4]))
    variant("two-parents", lambda d: d["nodes"][10].update(children=[9, 5]))
    variant("short-buffer", lambda d: d["buffers"][0].update(uri=d["buffers"][0]["uri"][:-16]))
    variant("missing-bin", lambda d: d["buffers"][0].update(uri="geometry.bin"))
    variant("accessor-too-long", lambda d: d["accessors"][2].update(count=4))
    variant("nan-translation", lambda d: d["nodes"][1]["translation"].__setitem__(0, math.nan))
    variant("inf-matrix", lambda d: d["nodes"][3].update(
        matrix=[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, math.inf, 0, 0, 1]))

    def overflow(d):
        d["nodes"][4]["scale"] = [1e300] * 3
        d["nodes"][5]["scale"] = [1e300] * 3
        d["nodes"][5]["translation"] = [1e300, 0, 0]
    variant("overflow", overflow)
    variant("flat-sun", lambda d: d["nodes"][8].update(scale=[0, 0, 0]))
    variant("flat-camera", lambda d: d["nodes"][11].update(scale=[1, 0, 1]))
    variant("zero-quaternion", lambda d: d["nodes"][4].update(rotation=[0, 0, 0, 0]))
    variant("ior-below-1", lambda d: d["materials"][1]["extensions"]["KHR_materials_ior"]
            .update(ior=0.5))
    variant("ior-huge", lambda d: d["materials"][1]["extensions"]["KHR_materials_ior"]
            .update(ior=1e20))
    variant("transmission", lambda d: d["materials"][1]["extensions"]
            ["KHR_materials_transmission"].update(transmissionFactor=1.5))
    variant("attenuation", lambda d: d["materials"][1]["extensions"]["KHR_materials_volume"]
            .update(attenuationDistance=1e-300))
    variant("cone", lambda d: L(d)[1]["spot"].update(innerConeAngle=0.7))
    variant("negative-intensity", lambda d: L(d)[0].update(intensity=-3.0))
    variant("float-intensity", lambda d: L(d)[0].update(intensity=3.5e38))
    variant("znear", lambda d: d["cameras"][0]["perspective"].update(znear=0.0))

    def up_along_view(d):
        del d["nodes"][9]["translation"]
        d["nodes"][9]["matrix"] = [1, 0, 0, 0, 0, 0, -1, 0, 0, 0, 1, 0, 0, 1, 5, 1]
    variant("up-along-view", up_along_view)
    variant("version-1", lambda d: d["asset"].update(version="1.0"))
    variant("draco", lambda d: d.update(extensionsRequired=["KHR_draco_mesh_compression"]))

    def no_scene(d):
        del d["scenes"]
        del d["scene"]
    variant("no-scene", no_scene)

    def images(d):
        signature = b"\x89PNG\r\n\x1a\n"
        d["images"] = [{"uri": data_uri(signature + b"\x7f" * 64, "image/png")},
                       {"uri": data_uri(signature + b"\0\0\0\rIHDR", "image/png")}]
        d["textures"] = [{"source": 0}, {"source": 1}]
        d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        d["materials"][2]["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {"index": 1}
    variant("images", images)

    def sparse(d):
        d["accessors"].append({"componentType": 5126, "count": 3, "type": "VEC3", "sparse": {
            "count": 1, "indices": {"bufferView": 1, "componentType": 5123},
            "values": {"bufferView": 2}}})
        d["meshes"][3]["primitives"][0]["attributes"]["POSITION"] = 3
    variant("sparse", sparse)
    return v


def gltf_text(doc):
    return json.dumps(doc, separators=(",", ":"), allow_nan=True)


def glb(doc, cut=0, version=2, json_length_delta=0):
    """A .glb of `doc` with the scene buffer as BIN chunk (as TestGLTFImporter's WriteGLB)."""
    doc = copy.deepcopy(doc)
    data = scene_buffer() if doc["buffers"][0]["byteLength"] == 96 else \
        base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
    del doc["buffers"][0]["uri"]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    total = 12 + 8 + len(text) + 8 + len(data)
    out = (b"glTF" + struct.pack("<II", version, total) +
           struct.pack("<I", len(text) + json_length_delta) + b"JSON" + text +
           struct.pack("<I", len(data)) + b"BIN\0" + data)
    return out[:len(out) - cut] if cut else out


def write_gltf():
    write("FuzzGLTF", "minimal.gltf", gltf_text(minimal_document()))
    write("FuzzGLTF", "scene.gltf", gltf_text(scene_document()))
    write("FuzzGLTF", "modes.gltf", gltf_text(modes_document()))
    write("FuzzGLTF", "animated.gltf", gltf_text(animated_document()))
    write("FuzzGLTF", "chain-20.gltf", json.dumps(chain_document(20)))
    for name, doc in gltf_variants().items():
        write("FuzzGLTF", name + ".gltf", gltf_text(doc))
    text = gltf_text(scene_document())
    write("FuzzGLTF", "truncated.gltf", text[:len(text) // 2])
    write("FuzzGLTF", "array.gltf", "[1, 2, 3]")

    write("FuzzGLB", "minimal.glb", glb(minimal_document()))
    write("FuzzGLB", "scene.glb", glb(scene_document()))
    write("FuzzGLB", "cut.glb", glb(scene_document(), cut=20))
    write("FuzzGLB", "version-1.glb", glb(minimal_document(), version=1))
    write("FuzzGLB", "json-past-end.glb", glb(minimal_document(), json_length_delta=4096))
    doc = minimal_document()
    text = json.dumps({**doc, "buffers": [{"byteLength": 36}]}).encode()
    text += b" " * (-len(text) % 4)
    write("FuzzGLB", "no-bin-chunk.glb",
          b"glTF" + struct.pack("<III", 2, 20 + len(text), len(text)) + b"JSON" + text)


# --- Meshes -------------------------------------------------------------------------------

TRIANGLE_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"


def write_obj():
    seeds = {
        "triangle.obj": TRIANGLE_OBJ + "f 1 2 3\n",
        "quad-uv-normals.obj": "mtllib scene.mtl\no quad\ng top\nusemtl white\ns 1\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
        "f 1/1/1 2/2/1 3/3/1 4/4/1\n",
        "forms.obj": TRIANGLE_OBJ + "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
        "f -3/-3/-1 -2/-2/-1 -1/-1/-1\nf 1/1/1 2/2/1 \\\n4/3/1\nv 1 1 0\nf 2/2/1 4/1/1 3/3/1\n"
        "l 1 2/1\np -1\n",
        "mixed-faces.obj": TRIANGLE_OBJ + "v 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n",
        "nan-normal.obj": TRIANGLE_OBJ + "vn 0 0 1\nvn nan 0 1\nf 1//1 2//2 3//1\n",
        "few-normals.obj": TRIANGLE_OBJ + "v 1 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n"
        "f 1//1 2//2 3//3\nf 2 4 3\n",
        "badface.obj": TRIANGLE_OBJ + "f 1 2 7\n",
        "far-normal.obj": TRIANGLE_OBJ + "vn 0 0 1\nf 1//100000000 2//100000000 3//100000000\n",
        "near-normal.obj": TRIANGLE_OBJ + "vn 0 0 1\nf 1//1 2//1 3//2\n",
        "far-texcoord.obj": TRIANGLE_OBJ + "vt 0 0\nf 1/1 2/99999999 3/1\n",
        "relative.obj": TRIANGLE_OBJ + "f -1 -2 -4\n",
        "relative-normal.obj": TRIANGLE_OBJ + "f 1//-1 2//-1 3//-1\nvn 0 0 1\n",
        "overflow.obj": TRIANGLE_OBJ + "vn 0 0 1\nf 1//1 2//1 3//99999999999999999999\n",
        "zero.obj": TRIANGLE_OBJ + "f 0 1 2\n",
        "words.obj": TRIANGLE_OBJ + "f 1/a 2 3\n",
        "slashes.obj": TRIANGLE_OBJ + "f 1/1/1/1 2 3\n",
        "mixed.obj": TRIANGLE_OBJ + "vn 0 0 1\nf 1//1 2 3\n",
        "badline.obj": TRIANGLE_OBJ + "l 1 9\n",
        "material.obj": TRIANGLE_OBJ + "usemtl " + "m" * 150 + "\nf 1 2 3\n",
        "nan.obj": "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n",
        "typo.obj": "v 0 0 0\nv 1 0 0\nv 0 1.0.0 0\nf 1 2 3\n",
        "inf.obj": TRIANGLE_OBJ + "v 1 inf 0\nf 1 2 4\n",
        "big.obj": TRIANGLE_OBJ + "v 1e39 0 0\nf 1 2 4\n",
        "points.obj": TRIANGLE_OBJ,
        "point.obj": "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n",
        "crlf.obj": TRIANGLE_OBJ.replace("\n", "\r\n") + "f 1 2 3\r\n",
        "continued-eof.obj": TRIANGLE_OBJ + "f 1 2 \\\n",
    }
    for name, text in seeds.items():
        write("FuzzOBJ", name, text)


def binary_stl(declared, written, nan_at=None):
    out = b"binary stl".ljust(80, b" ") + struct.pack("<I", declared)
    for t in range(written):
        values = [0, 0, 1, t, 0, 0, t + 1, 0, 0, t, 1, 0]
        if nan_at == t:
            values[4] = math.nan
        out += struct.pack("<12f", *values) + b"\0\0"
    return out


ASCII_STL = ("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
             "endloop\nendfacet\nendsolid s\n")


def write_stl():
    write("FuzzSTL", "ascii.stl", ASCII_STL)
    write("FuzzSTL", "ascii-upper.stl", ASCII_STL.upper())
    write("FuzzSTL", "binary.stl", binary_stl(2, 2))
    write("FuzzSTL", "binary-solid-header.stl", b"solid" + binary_stl(1, 1)[5:])
    write("FuzzSTL", "cut.stl", binary_stl(5, 2))
    write("FuzzSTL", "nan.stl", binary_stl(2, 2, nan_at=1))
    write("FuzzSTL", "nan-ascii.stl", ASCII_STL.replace("vertex 1 0 0", "vertex 1 nan 0"))
    write("FuzzSTL", "cut-ascii.stl", ASCII_STL[:ASCII_STL.index("vertex 0 1 0")])
    write("FuzzSTL", "garbage.stl", "garbage\nmore garbage\n")
    write("FuzzSTL", "degenerate.stl", ASCII_STL.replace("vertex 0 1 0", "vertex 2 0 0"))


def ply_header(vertices, faces, normals=False, fmt="ascii"):
    return ("ply\nformat %s 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
            "property float z\n%selement face %d\nproperty list uchar int vertex_indices\n"
            "end_header\n" % (fmt, vertices,
                              "property float nx\nproperty float ny\nproperty float nz\n"
                              if normals else "", faces))


def bunny_cut(vertices):
    """Data/bunny.ply's header with its first `vertices` vertices and the faces among them."""
    with open(os.path.join(DATA, "bunny.ply")) as f:
        lines = f.read().split("\n")
    body = lines[lines.index("end_header") + 1:]
    counts = [int(l.split()[2]) for l in lines if l.startswith("element")]
    points = body[:vertices]
    faces = [l for l in body[counts[0]:counts[0] + counts[1]]
             if all(int(i) < vertices for i in l.split()[1:])]
    header = lines[:lines.index("end_header") + 1]
    header = [("element vertex %d" % vertices) if l.startswith("element vertex") else
              ("element face %d" % len(faces)) if l.startswith("element face") else l
              for l in header]
    return "\n".join(header + points + faces) + "\n"


def write_ply():
    triangle = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
    write("FuzzPLY", "ascii.ply", ply_header(3, 1) + triangle)
    bunny = bunny_cut(60)
    write("FuzzPLY", "bunny-cut.ply", bunny)
    write("FuzzPLY", "bunny-cut-truncated.ply", bunny[:len(bunny) // 2])
    write("FuzzPLY", "normals.ply", ply_header(3, 1, True) +
          "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n")
    write("FuzzPLY", "inf-normal.ply", ply_header(3, 1, True) +
          "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 inf 0 1\n3 0 1 2\n")
    write("FuzzPLY", "nan.ply", ply_header(3, 1) + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n")
    write("FuzzPLY", "flat.ply", ply_header(4, 2) + "0 0 0\n1 1 1\n2 2 2\n0 0 0\n3 0 1 2\n3 0 3 1\n")
    write("FuzzPLY", "mostly-flat.ply",
          ply_header(4, 2) + "0 0 0\n1 1 1\n2 2 2\n0 1 0\n3 0 1 2\n3 0 1 3\n")
    write("FuzzPLY", "badface.ply", ply_header(3, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n")
    write("FuzzPLY", "quad.ply", ply_header(4, 1) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")
    vertices = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    write("FuzzPLY", "binary-le.ply", ply_header(3, 1, fmt="binary_little_endian").encode() +
          vertices + b"\3" + struct.pack("<3i", 0, 1, 2))
    write("FuzzPLY", "binary-be.ply", ply_header(3, 1, fmt="binary_big_endian").encode() +
          struct.pack(">9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + b"\3" + struct.pack(">3i", 0, 1, 2))
    write("FuzzPLY", "binary-cut.ply", ply_header(3, 1, fmt="binary_little_endian").encode() +
          vertices + b"\3" + struct.pack("<2i", 0, 1))
    write("FuzzPLY", "colours-and-edges.ply",
          "ply\nformat ascii 1.0\ncomment colours\nobj_info test\nelement vertex 3\n"
          "property double x\nproperty double y\nproperty double z\nproperty uchar red\n"
          "property uchar green\nproperty uchar blue\nelement face 1\n"
          "property list uint8 uint32 vertex_index\nelement edge 1\nproperty int vertex1\n"
          "property int vertex2\nend_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n"
          "3 0 1 2\n0 1\n")
    write("FuzzPLY", "garbage.ply", "hello\n")
    write("FuzzPLY", "no-end-header.ply", "ply\nformat ascii 1.0\ncomment " + "c" * 200)


if __name__ == "__main__":
    shutil.rmtree(CORPUS, ignore_errors=True)
    write_gltf()
    write_obj()
    write_stl()
    write_ply()
    for target in sorted(os.listdir(CORPUS)):
        files = os.listdir(os.path.join(CORPUS, target))
        size = sum(os.path.getsize(os.path.join(CORPUS, target, f)) for f in files)
        print("%s: %d seeds, %d bytes" % (target, len(files), size))
