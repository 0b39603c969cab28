#!/usr/bin/env python3
"""Writes the loaders' seed inputs (one tiny triangle or quad per format) into
OUT/<format>/: generated here rather than committed, since the repository holds
no model files. The fuzzers grow their corpora from these.
    python3 tests/fuzz/make_seeds.py OUT"""
import base64
import json
import struct
import sys
from pathlib import Path

TEXT_SEEDS = {
    "obj/quad.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n",
    "off/quad.off": "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n",
    "ply/triangle.ply": "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    "stl/triangle.stl": "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                        "endloop\nendfacet\nendsolid t\n",
}

# One triangle: three float positions, then three uint16 indices padded to 4 bytes.
BUFFER = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"


def gltf_document(buffer):
    return {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 0.5]}, "alphaMode": "BLEND"}],
        "buffers": [buffer],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }


def glb(document, binary):
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)  # chunks are 4-byte aligned; JSON pads with spaces
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


def main(out):
    out = Path(out)
    for name, text in TEXT_SEEDS.items():
        (out / name).parent.mkdir(parents=True, exist_ok=True)
        (out / name).write_text(text)
    uri = "data:application/octet-stream;base64," + base64.b64encode(BUFFER).decode()
    (out / "gltf").mkdir(parents=True, exist_ok=True)
    (out / "gltf/triangle.gltf").write_text(json.dumps(gltf_document({"byteLength": len(BUFFER), "uri": uri})))
    (out / "glb").mkdir(parents=True, exist_ok=True)
    (out / "glb/triangle.glb").write_bytes(glb(gltf_document({"byteLength": len(BUFFER)}), BUFFER))


if __name__ == "__main__":
    main(sys.argv[1])
