#!/usr/bin/env python3
"""Writes a small textured glTF scene for trying prt's texture support, and the same scene with the
texture replaced by its mean colour (for comparison).

Usage: scripts/textured-example.py DIR
Writes DIR/bricks.png (a procedural brick texture, sRGB), DIR/corner.gltf + corner.bin (a grey
floor, a brick wall textured with REPEAT, a white box) and DIR/corner_flat.gltf (the wall flat at
the texture's mean linear colour). docs/images/textures.png was made with:

  scripts/textured-example.py out/tex
  for s in corner corner_flat; do
    prt bake out/tex/$s.gltf -o out/tex/$s.prt --transfer interreflected --order 6 --samples 512
    prt relight out/tex/$s.gltf out/tex/$s.prt data/sky.hdr -o out/tex/$s.png --size 400x300 \
      --exposure -1.5
  done
  oiiotool out/tex/corner_flat.png out/tex/corner.png --mosaic 2x1 -o docs/images/textures.png
"""
import json
import os
import struct
import sys
import zlib


def brick_texture(width=256, height=128):
    """RGB bytes of a running-bond brick pattern: bricks 64 x 32 texels, 4-texel mortar."""
    rows = []
    for y in range(height):
        row = bytearray()
        course = y // 32
        for x in range(width):
            shifted = x + (32 if course % 2 else 0)
            brick = (shifted // 64) % (width // 64)
            mortar = y % 32 < 4 or shifted % 64 < 4
            if mortar:
                row += bytes((200, 195, 185))
            else:
                k = (brick * 7 + course * 13) % 5  # a little variation per brick
                row += bytes((150 + 12 * k, 55 + 5 * k, 40 + 4 * k))
        rows.append(bytes(row))
    return rows


def png(rows, width, height):
    raw = b"".join(b"\0" + r for r in rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
            + chunk(b"IEND", b""))


def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def look_at_quaternion(eye, target):
    """The (x, y, z, w) rotation that turns a glTF camera (looking down -Z, +Y up) toward target."""
    f = [target[k] - eye[k] for k in range(3)]
    n = sum(x * x for x in f) ** 0.5
    f = [x / n for x in f]
    r = [f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0]  # cross(f, +Y)
    n = sum(x * x for x in r) ** 0.5
    r = [x / n for x in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    m = [[r[0], u[0], -f[0]], [r[1], u[1], -f[1]], [r[2], u[2], -f[2]]]  # columns X, Y, Z
    w = (max(0.0, 1 + m[0][0] + m[1][1] + m[2][2])) ** 0.5 / 2
    return [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w),
            (m[1][0] - m[0][1]) / (4 * w), w]


def grid(corner, edge_u, edge_v, nu, nv, uv_scale):
    """Vertices (position, normal, uv) and triangles of a parallelogram grid facing
    cross(edge_u, edge_v)."""
    n = [edge_u[1] * edge_v[2] - edge_u[2] * edge_v[1], edge_u[2] * edge_v[0] - edge_u[0] * edge_v[2],
         edge_u[0] * edge_v[1] - edge_u[1] * edge_v[0]]
    length = sum(x * x for x in n) ** 0.5
    n = [x / length for x in n]
    verts, tris = [], []
    for j in range(nv + 1):
        for i in range(nu + 1):
            s, t = i / nu, j / nv
            p = [corner[k] + s * edge_u[k] + t * edge_v[k] for k in range(3)]
            verts.append((p, n, (s * uv_scale[0], (1 - t) * uv_scale[1])))
    for j in range(nv):
        for i in range(nu):
            a = j * (nu + 1) + i
            b, c, d = a + 1, a + nu + 1, a + nu + 2
            tris += [(a, b, d), (a, d, c)]
    return verts, tris


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/tex"
    os.makedirs(out, exist_ok=True)
    rows = brick_texture()
    with open(os.path.join(out, "bricks.png"), "wb") as f:
        f.write(png(rows, 256, 128))
    total = [0.0, 0.0, 0.0]
    for r in rows:
        for x in range(256):
            for c in range(3):
                total[c] += srgb_to_linear(r[3 * x + c] / 255)
    mean = [t / (256 * 128) for t in total]

    # Floor (grey), back wall (bricks, 4 x 2.5 repeats), a white box standing by the wall.
    parts = [("floor", [grid([-3, 0, -2.5], [0, 0, 5], [6, 0, 0], 40, 40, (1, 1))], 0),
             ("wall", [grid([-3, 0, -2.5], [6, 0, 0], [0, 2.5, 0], 48, 20, (4, 2.5))], 1)]
    lo, hi = [-0.6, 0.0, -1.9], [0.4, 1.0, -0.9]
    box = []
    for axis in range(3):
        for sign in (1, -1):
            u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3
            corner = [lo[k] for k in range(3)]
            if sign > 0:
                corner[axis] = hi[axis]
            eu = [0.0] * 3
            ev = [0.0] * 3
            eu[u_axis] = hi[u_axis] - lo[u_axis]
            ev[v_axis] = hi[v_axis] - lo[v_axis]
            if sign < 0:
                eu, ev = ev, eu
            box.append(grid(corner, eu, ev, 6, 6, (1, 1)))
    parts.append(("box", box, 2))

    for flat in (False, True):
        blob = bytearray()
        doc = {"asset": {"version": "2.0", "generator": "scripts/textured-example.py"},
               "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "accessors": [],
               "bufferViews": [], "buffers": [],
               "materials": [
                   {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1]}},
                   {"name": "bricks", "pbrMetallicRoughness":
                       {"baseColorFactor": mean + [1]} if flat else
                       {"baseColorTexture": {"index": 0}}},
                   {"name": "white", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1]}}]}
        if not flat:
            doc["textures"] = [{"source": 0, "sampler": 0}]
            doc["samplers"] = [{"wrapS": 10497, "wrapT": 10497}]
            doc["images"] = [{"uri": "bricks.png"}]

        def view(data, count, kind, component, minmax=None):
            while len(blob) % 4:
                blob.append(0)
            doc["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
            blob.extend(data)
            accessor = {"bufferView": len(doc["bufferViews"]) - 1, "componentType": component,
                        "count": count, "type": kind}
            if minmax:
                accessor["min"], accessor["max"] = minmax
            doc["accessors"].append(accessor)
            return len(doc["accessors"]) - 1

        for name, grids, material in parts:
            verts, tris = [], []
            for gv, gt in grids:
                base = len(verts)
                verts += gv
                tris += [(a + base, b + base, c + base) for a, b, c in gt]
            pos = b"".join(struct.pack("<3f", *v[0]) for v in verts)
            lo_p = [min(v[0][k] for v in verts) for k in range(3)]
            hi_p = [max(v[0][k] for v in verts) for k in range(3)]
            attributes = {"POSITION": view(pos, len(verts), "VEC3", 5126, (lo_p, hi_p)),
                          "NORMAL": view(b"".join(struct.pack("<3f", *v[1]) for v in verts),
                                         len(verts), "VEC3", 5126),
                          "TEXCOORD_0": view(b"".join(struct.pack("<2f", *v[2]) for v in verts),
                                             len(verts), "VEC2", 5126)}
            indices = view(b"".join(struct.pack("<3I", *t) for t in tris), 3 * len(tris), "SCALAR",
                           5125)
            doc["meshes"].append({"name": name, "primitives": [
                {"attributes": attributes, "indices": indices, "material": material}]})
            doc["nodes"].append({"mesh": len(doc["meshes"]) - 1, "name": name})
            doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
        doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.75, "znear": 0.05}}]
        eye, target = [1.9, 1.5, 2.4], [-0.4, 0.7, -1.6]
        doc["nodes"].append({"camera": 0, "name": "view", "translation": eye,
                             "rotation": look_at_quaternion(eye, target)})
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
        stem = "corner_flat" if flat else "corner"
        doc["buffers"] = [{"uri": stem + ".bin", "byteLength": len(blob)}]
        with open(os.path.join(out, stem + ".bin"), "wb") as f:
            f.write(blob)
        with open(os.path.join(out, stem + ".gltf"), "w") as f:
            json.dump(doc, f, indent=1)
    print("wrote", out, "(texture mean, linear:", ", ".join(f"{m:.4f}" for m in mean) + ")")


if __name__ == "__main__":
    main()
