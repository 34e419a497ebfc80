#!/usr/bin/env python3
"""Writes a level-sized OBJ scene for glossy bakes at scale: a subdivided ground plus a few
spheres to be made glossy with `prt bake --material glossyN=...`.

The ground is a G x G grid of vertices (G = round(sqrt(ground vertices))) over a 100 x 100
square at y = 0, object "ground"; the spheres (radius 3, `--sphere-segments` around, half that
many rings) are objects "glossy0".."glossy{n-1}" standing on it. Normals are written (+Y on the
ground, radial on the spheres). Prints the vertex and triangle counts.

    scripts/glossy-scale-scene.py --ground-vertices 1000000 --spheres 4 -o scale.obj
"""
import argparse
import math
import sys


def write_ground(out, g, size, base):
    step = size / (g - 1)
    for j in range(g):
        z = -size / 2 + j * step
        out.write("".join(f"v {-size / 2 + i * step:.6f} 0 {z:.6f}\n" for i in range(g)))
    out.write("vn 0 1 0\n")
    out.write("o ground\n")
    for j in range(g - 1):
        row = base + j * g
        lines = []
        for i in range(g - 1):
            a, b, c, d = row + i, row + i + 1, row + g + i, row + g + i + 1
            # Counter-clockwise seen from +Y: the front faces up.
            lines.append(f"f {a}//1 {c}//1 {b}//1\nf {b}//1 {c}//1 {d}//1\n")
        out.write("".join(lines))
    return g * g, 2 * (g - 1) * (g - 1)


def write_sphere(out, index, centre, radius, seg, base_v, base_n):
    rings = max(2, seg // 2)
    verts = [(0.0, 1.0, 0.0)]
    for r in range(1, rings):
        th = math.pi * r / rings
        for s in range(seg):
            ph = 2 * math.pi * s / seg
            verts.append((math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)))
    verts.append((0.0, -1.0, 0.0))
    for (x, y, z) in verts:
        out.write(f"v {centre[0] + radius * x:.6f} {centre[1] + radius * y:.6f} "
                  f"{centre[2] + radius * z:.6f}\n")
    for (x, y, z) in verts:
        out.write(f"vn {x:.6f} {y:.6f} {z:.6f}\n")
    out.write(f"o glossy{index}\n")
    tris = []
    top, bottom = 0, len(verts) - 1

    def ring(r, s):  # vertex of ring r (1 .. rings-1), segment s
        return 1 + (r - 1) * seg + s % seg

    for s in range(seg):  # outward-facing, counter-clockwise seen from outside
        tris.append((top, ring(1, s + 1), ring(1, s)))
        tris.append((bottom, ring(rings - 1, s), ring(rings - 1, s + 1)))
    for r in range(1, rings - 1):
        for s in range(seg):
            a, b = ring(r, s), ring(r, s + 1)
            c, d = ring(r + 1, s), ring(r + 1, s + 1)
            tris.append((a, b, c))
            tris.append((b, d, c))
    out.write("".join(
        f"f {base_v + a}//{base_n + a} {base_v + b}//{base_n + b} {base_v + c}//{base_n + c}\n"
        for (a, b, c) in tris))
    return len(verts), len(tris)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--ground-vertices", type=int, default=1000000)
    p.add_argument("--spheres", type=int, default=4)
    p.add_argument("--sphere-segments", type=int, default=96)
    p.add_argument("-o", "--output", required=True)
    a = p.parse_args()
    g = max(2, round(math.sqrt(a.ground_vertices)))
    if a.spheres < 0 or a.spheres > 16 or a.sphere_segments < 3:
        sys.exit("glossy-scale-scene.py: --spheres must be in [0, 16], --sphere-segments >= 3")
    with open(a.output, "w") as out:
        out.write("# glossy-scale-scene.py: ground grid plus spheres\n")
        v, t = write_ground(out, g, 100.0, 1)
        base_n = 2
        for k in range(a.spheres):
            ang = 2 * math.pi * k / max(1, a.spheres) + math.pi / 4
            centre = (15 * math.cos(ang), 3.0, 15 * math.sin(ang))
            sv, st = write_sphere(out, k, centre, 3.0, a.sphere_segments, v + 1, base_n)
            v += sv
            t += st
            base_n += sv
    print(f"{a.output}: {v} vertices, {t} triangles ({g}x{g} ground, {a.spheres} spheres)")


if __name__ == "__main__":
    main()
