# SPDX-License-Identifier: MIT
"""glTF 2.0 test files built from numpy arrays, written as .glb, as .gltf
with a .bin beside it, or as .gltf with a base64 data: URI.

Independent of keyrot: it follows the glTF 2.0 specification's layout rules
(little-endian, 4-byte aligned accessors, GLB chunks padded to 4 bytes).
"""
import base64
import json
import os
import struct
import subprocess

import numpy as np

FLOAT, BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT, UNSIGNED_INT = 5126, 5120, 5121, 5122, 5123, 5125
NUMPY_TYPE = {FLOAT: "<f4", BYTE: "<i1", UNSIGNED_BYTE: "<u1", SHORT: "<i2", UNSIGNED_SHORT: "<u2", UNSIGNED_INT: "<u4"}
TYPE_OF_WIDTH = {1: "SCALAR", 3: "VEC3", 4: "VEC4", 16: "MAT4"}
SIGNED_MAX = {BYTE: 127, SHORT: 32767}
UNSIGNED_MAX = {UNSIGNED_BYTE: 255, UNSIGNED_SHORT: 65535}


def quantize(values, component):
    """Values as a normalised integer type stores them (the spec's rounding)."""
    if component in SIGNED_MAX:
        return np.round(np.clip(values, -1, 1) * SIGNED_MAX[component])
    return np.round(np.clip(values, 0, 1) * UNSIGNED_MAX[component])


def dequantize(stored, component):
    """The specification's decoding of normalised integers."""
    if component == FLOAT:
        return stored.astype(np.float32).astype(np.float64)
    if component in SIGNED_MAX:
        return np.maximum(stored / SIGNED_MAX[component], -1.0)
    return stored / UNSIGNED_MAX[component]


class Builder:
    """Collects accessors into one buffer, and nodes, a skin and animations into the JSON."""

    def __init__(self):
        self.bin = bytearray()
        self.json = {"asset": {"version": "2.0", "generator": "keyrot tests"}, "scene": 0,
                     "scenes": [{"nodes": [0]}], "nodes": [], "accessors": [], "bufferViews": [],
                     "buffers": [], "animations": []}

    def view(self, data, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            view["byteStride"] = stride
        self.bin += data
        self.json["bufferViews"].append(view)
        return len(self.json["bufferViews"]) - 1

    def accessor(self, values, component=FLOAT, stride=None, minmax=False, sparse_every=None):
        """`values` (n x width, or n) stored as `component` (normalised when an integer type).
        sparse_every: every that many elements is stored as a sparse substitute (UNSIGNED_SHORT
        indices), the bufferView holding the first element in its place."""
        values = np.asarray(values, dtype=np.float64)
        substitutes = None
        if sparse_every:
            indices = np.arange(0, len(values), sparse_every)
            substitutes = (indices, values[indices].copy())
            values = values.copy()
            values[indices] = values[0]
        width = 1 if values.ndim == 1 else values.shape[1]
        stored = values.astype(np.float32) if component == FLOAT else quantize(values, component)
        row = stored.reshape(len(values), width).astype(NUMPY_TYPE[component]).tobytes()
        element = np.dtype(NUMPY_TYPE[component]).itemsize * width
        if stride and stride > element:  # interleave with padding bytes
            rows = [row[i * element:(i + 1) * element] + b"\xab" * (stride - element) for i in range(len(values))]
            data = b"".join(rows)
        else:
            data = row
        acc = {"bufferView": self.view(data, stride), "componentType": component, "count": len(values),
               "type": TYPE_OF_WIDTH[width]}
        if component != FLOAT:
            acc["normalized"] = True
        if minmax or width == 1:
            # (the stored integers for a normalised accessor, as the specification asks)
            decoded = stored.reshape(len(values), width).astype(np.float64)
            acc["min"] = [float(v) for v in decoded.min(axis=0)]
            acc["max"] = [float(v) for v in decoded.max(axis=0)]
        if substitutes is not None:
            indices, replaced = substitutes
            sub = replaced.astype(np.float32) if component == FLOAT else quantize(replaced, component)
            acc["sparse"] = {"count": len(indices),
                             "indices": {"bufferView": self.view(indices.astype("<u2").tobytes()),
                                         "componentType": UNSIGNED_SHORT},
                             "values": {"bufferView": self.view(sub.astype(NUMPY_TYPE[component]).tobytes())}}
        self.json["accessors"].append(acc)
        return len(self.json["accessors"]) - 1

    def decoded(self, values, component=FLOAT):
        """What a reader gets back from accessor(values, component)."""
        values = np.asarray(values, dtype=np.float64)
        stored = values.astype(np.float32) if component == FLOAT else quantize(values, component)
        return dequantize(stored, component)

    def decoded_times(self, times):
        """The key times keyrot reads from accessor(times): where every stored float is the one nearest
        k/fps for one rate (the first step's, its NTSC rate, or 24, 25, 30, 48, 50, 60 or 120), k/fps;
        else each the shortest decimal that reads back as its float."""
        stored = np.asarray(times, dtype=np.float64).astype(np.float32)
        first = round(1 / (float(stored[1]) - float(stored[0]))) if len(stored) > 1 else 0
        for fps in (first, 1000 * first / 1001, 24, 25, 30, 48, 50, 60, 120):
            if fps > 0:
                k = np.rint(stored.astype(np.float64) * fps)
                if np.array_equal((k / fps).astype(np.float32), stored):
                    return k / fps
        return np.array([float(np.format_float_positional(t, unique=True)) for t in stored])

    def skeleton(self, joints, names=True):
        """A chain-and-branches hierarchy of `joints` nodes under node 0, with a skinned triangle."""
        for j in range(joints):
            node = {"translation": [0.0, 0.1 * (j % 5), 0.0]}
            if names:
                node["name"] = f"joint{j}"
            self.json["nodes"].append(node)
        for j in range(1, joints):
            parent = (j - 1) // 2
            self.json["nodes"][parent].setdefault("children", []).append(j)
        positions = self.accessor(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float), minmax=True)
        joints_attr = self.accessor_raw(np.zeros((3, 4), dtype="<u1"), UNSIGNED_BYTE, "VEC4")
        weights = self.accessor(np.tile([1.0, 0, 0, 0], (3, 1)))
        ibm = self.accessor(np.tile(np.eye(4).reshape(16), (joints, 1)))
        self.json["meshes"] = [{"primitives": [{"attributes": {"POSITION": positions, "JOINTS_0": joints_attr,
                                                               "WEIGHTS_0": weights}}]}]
        self.json["skins"] = [{"joints": list(range(joints)), "inverseBindMatrices": ibm}]
        self.json["nodes"].append({"name": "body", "mesh": 0, "skin": 0})
        self.json["scenes"][0]["nodes"].append(joints)

    def morph_mesh(self, targets, weights=None):
        """A mesh of one triangle with `targets` morph targets; returns its index."""
        positions = self.accessor(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float), minmax=True)
        mesh = {"primitives": [{"attributes": {"POSITION": positions},
                                "targets": [{"POSITION": self.accessor(0.1 * (j + 1) * np.eye(3), minmax=True)}
                                            for j in range(targets)]}]}
        if weights is not None:
            mesh["weights"] = weights
        self.json.setdefault("meshes", []).append(mesh)
        return len(self.json["meshes"]) - 1

    def detailed_mesh(self, vertices):
        """A node of a mesh of `vertices` vertices (12 bytes each) in the scene: a file whose buffer
        is mostly a model's, not its animation's."""
        points = np.random.default_rng(vertices).normal(size=(vertices, 3))
        self.json.setdefault("meshes", []).append(
            {"primitives": [{"attributes": {"POSITION": self.accessor(points, minmax=True)}, "mode": 0}]})
        self.json["nodes"].append({"name": "model", "mesh": len(self.json["meshes"]) - 1})
        self.json["scenes"][0]["nodes"].append(len(self.json["nodes"]) - 1)

    def accessor_raw(self, array, component, type_):
        acc = {"bufferView": self.view(array.tobytes()), "componentType": component, "count": len(array), "type": type_}
        self.json["accessors"].append(acc)
        return len(self.json["accessors"]) - 1

    def animation(self, channels, name=None):
        """channels: dicts of node, path, times, values (keys x width; CUBICSPLINE: keys x 3 x width as
        in-tangent, value, out-tangent), interpolation, and optionally component and stride."""
        anim = {"channels": [], "samplers": []}
        if name:
            anim["name"] = name
        for c in channels:
            values = np.asarray(c["values"], dtype=float)
            width = values.shape[-1]
            out = self.accessor(values.reshape(-1, width), c.get("component", FLOAT), c.get("stride"),
                                sparse_every=c.get("sparse_every"))
            anim["samplers"].append({"input": self.accessor(c["times"]), "output": out,
                                     "interpolation": c.get("interpolation", "LINEAR")})
            anim["channels"].append({"sampler": len(anim["samplers"]) - 1, "target": {"node": c["node"], "path": c["path"]}})
        self.json["animations"].append(anim)

    def write(self, path, how):
        """how: 'glb', 'bin' (a .gltf with NAME.bin beside it) or 'datauri'."""
        while len(self.bin) % 4:
            self.bin.append(0)
        doc = json.loads(json.dumps(self.json))
        doc["buffers"] = [{"byteLength": len(self.bin)}]
        if how == "bin":
            bin_name = path.rsplit("/", 1)[-1].rsplit(".", 1)[0] + ".bin"
            doc["buffers"][0]["uri"] = bin_name
            with open(path.rsplit("/", 1)[0] + "/" + bin_name if "/" in path else bin_name, "wb") as f:
                f.write(self.bin)
        elif how == "datauri":
            doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()
        text = json.dumps(doc).encode()
        if how != "glb":
            with open(path, "wb") as f:
                f.write(text)
            return
        with open(path, "wb") as f:
            f.write(glb(text, bytes(self.bin)))


def glb(text, binary):
    """The GLB container of a JSON text and a BIN chunk."""
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text
    if binary:
        chunks += struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def parts(path):
    """The JSON of a .glb or .gltf, and its buffer's bytes (the BIN chunk, the .bin, a data: URI)."""
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        n = struct.unpack_from("<I", data, 12)[0]
        doc = json.loads(data[20:20 + n])
        return doc, data[20 + n + 8:]
    doc = json.loads(data)
    uri = doc["buffers"][0]["uri"]
    if uri.startswith("data:"):
        return doc, base64.b64decode(uri.split(",", 1)[1])
    return doc, open(os.path.join(os.path.dirname(path), uri), "rb").read()


def validator_problems(validator, files):
    """What the Khronos glTF Validator (tests/gltf_validate.js) reports of `files`: a list of
    lines, empty when every file has no errors and no warnings."""
    p = subprocess.run(["node", validator] + files, capture_output=True, text=True)
    bad = [line for line in p.stdout.splitlines() if not line.endswith(": 0 errors, 0 warnings")]
    if p.returncode != 0 and not bad:
        bad = [p.stderr[-500:]]
    return bad
