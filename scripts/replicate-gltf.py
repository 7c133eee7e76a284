#!/usr/bin/env python3
"""Writes a .glb holding N copies of a .glb's scene side by side along x: the nodes are copied,
the meshes shared. For measurements on larger models than the corpus has (the HRA body three
times is 1.18 million triangles in the scene), with the nesting of the original in each copy.

    scripts/replicate-gltf.py IN.glb OUT.glb N
"""
import copy
import json
import struct
import sys

GLB_MAGIC, JSON_CHUNK, BIN_CHUNK = 0x46546C67, 0x4E4F534A, 0x004E4942


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    src, dst, copies = sys.argv[1], sys.argv[2], int(sys.argv[3])
    data = open(src, 'rb').read()
    magic, _, length = struct.unpack_from('<III', data, 0)
    if magic != GLB_MAGIC:
        sys.exit(f'{src}: not a binary glTF (.glb) file')
    chunks, offset = {}, 12
    while offset < length:
        size, kind = struct.unpack_from('<II', data, offset)
        chunks[kind] = data[offset + 8:offset + 8 + size]
        offset += 8 + size
    doc = json.loads(chunks[JSON_CHUNK])
    binary = chunks.get(BIN_CHUNK, b'')
    nodes = doc['nodes']
    scene = doc['scenes'][doc.get('scene', 0)]
    roots = list(scene['nodes'])

    # Copies one model width apart (plus a fifth), from the accessors' position bounds.
    xs = [v for mesh in doc['meshes'] for prim in mesh['primitives']
          for key in ('min', 'max') if key in doc['accessors'][prim['attributes']['POSITION']]
          for v in [doc['accessors'][prim['attributes']['POSITION']][key][0]]]
    spacing = (max(xs) - min(xs)) * 1.2 if xs else 1.0

    def copy_node(index):
        node = copy.deepcopy(nodes[index])
        children = [copy_node(k) for k in node.get('children', [])]
        node.pop('children', None)
        if children:
            node['children'] = children
        nodes.append(node)
        return len(nodes) - 1

    scene['nodes'] = []
    for c in range(copies):
        children = roots if c == 0 else [copy_node(r) for r in roots]
        nodes.append({'name': f'copy{c}', 'translation': [spacing * c, 0, 0], 'children': children})
        scene['nodes'].append(len(nodes) - 1)

    text = json.dumps(doc).encode()
    text += b' ' * (-len(text) % 4)
    binary += b'\0' * (-len(binary) % 4)
    total = 12 + 8 + len(text) + (8 + len(binary) if binary else 0)
    out = struct.pack('<III', GLB_MAGIC, 2, total) + struct.pack('<II', len(text), JSON_CHUNK) + text
    if binary:
        out += struct.pack('<II', len(binary), BIN_CHUNK) + binary
    open(dst, 'wb').write(out)


if __name__ == '__main__':
    main()
