#!/usr/bin/env python3
"""Writes two mesh files from the HRA left kidney (tests/data/models/HRA_Kidney_Female_Left):
the capsule as a binary STL and the eleven renal pyramids as one binary little-endian PLY, in the
glTF file's world coordinates (metres, y up). Run from the repository root."""
import json, struct, pathlib

root = pathlib.Path(__file__).resolve().parents[4]
glb = (root / "tests/data/models/HRA_Kidney_Female_Left/VH_F_Kidney_L.glb").read_bytes()
json_length = struct.unpack_from("<I", glb, 12)[0]
doc = json.loads(glb[20:20 + json_length])
bin_offset = 20 + json_length + 8

def accessor(index):
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    start = bin_offset + view.get("byteOffset", 0) + a.get("byteOffset", 0)
    width = {"SCALAR": 1, "VEC3": 3}[a["type"]]
    fmt = {5126: "f", 5125: "I", 5123: "H"}[a["componentType"]]
    size = struct.calcsize(fmt)
    stride = view.get("byteStride", size * width)
    return [struct.unpack_from("<" + fmt * width, glb, start + i * stride) for i in range(a["count"])]

def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]

def local(node):
    if "matrix" in node:
        m = node["matrix"]
        return [[m[c * 4 + r] for c in range(4)] for r in range(4)]
    assert "rotation" not in node and "scale" not in node, "only translations expected"
    t = node.get("translation", [0, 0, 0])
    return [[1, 0, 0, t[0]], [0, 1, 0, t[1]], [0, 0, 1, t[2]], [0, 0, 0, 1]]

world = {}
def walk(index, parent):
    world[index] = matmul(parent, local(doc["nodes"][index]))
    for child in doc["nodes"][index].get("children", []):
        walk(child, world[index])
identity = [[float(i == j) for j in range(4)] for i in range(4)]
for r in doc["scenes"][doc.get("scene", 0)]["nodes"]:
    walk(r, identity)

def triangles(name_prefix):
    positions, faces = [], []
    for index, node in enumerate(doc["nodes"]):
        if "mesh" not in node or not node.get("name", "").startswith(name_prefix):
            continue
        m = world[index]
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            base = len(positions)
            for p in accessor(prim["attributes"]["POSITION"]):
                positions.append(tuple(sum(m[r][k] * (list(p) + [1.0])[k] for k in range(4)) for r in range(3)))
            idx = [i[0] for i in accessor(prim["indices"])]
            faces += [(base + idx[i], base + idx[i + 1], base + idx[i + 2]) for i in range(0, len(idx), 3)]
    return positions, faces

out = pathlib.Path(__file__).resolve().parent
positions, faces = triangles("VH_F_kidney_capsule_L")
with open(out / "kidney-capsule.stl", "wb") as f:
    f.write(b"kidney capsule (HRA, CC BY 4.0)".ljust(80, b" ") + struct.pack("<I", len(faces)))
    for t in faces:
        f.write(struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *positions[i]) for i in t) + b"\0\0")
positions, faces = triangles("VH_F_renal_pyramid_L")
with open(out / "renal-pyramids.ply", "wb") as f:
    f.write(("ply\nformat binary_little_endian 1.0\ncomment renal pyramids (HRA, CC BY 4.0)\n"
             f"element vertex {len(positions)}\nproperty float x\nproperty float y\nproperty float z\n"
             f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n").encode())
    for p in positions:
        f.write(struct.pack("<3f", *p))
    for t in faces:
        f.write(struct.pack("<B3i", 3, *t))
