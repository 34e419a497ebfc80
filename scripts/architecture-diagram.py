#!/usr/bin/env python3
"""Writes docs/images/architecture.svg: prt's layers, what each holds and what it links.

Usage: scripts/architecture-diagram.py [OUT.svg]. Each layer uses only the layers below it; boxes
side by side in one row (bake/, radiosity/) do not use each other.
"""
import pathlib
import sys

LAYERS = [  # rows, top to bottom; each row's boxes: (folder, CMake target, what it holds, third-party)
    [("cli/", "prt", "argument mapping, one file per subcommand", "CLI11")],
    [("report/", "prt::report", "path-traced ground truths, sweeps, plots, stability suite",
      "nlohmann-json")],
    [("relight/", "prt::relight", "image I/O, camera, renderer, tone mapping, sky, relight pipeline, "
      "drawing radiosity results", "OpenImageIO (plugin, on first use)")],
    [("bake/", "prt::bake", "transfer baker, samplers, interreflection, Haar, adaptive/", "TBB"),
     ("radiosity/", "prt::radiosity", "form factors, solvers, patch refinement, scene solve",
      "TBB")],
    [("scene/", "prt::scene", "scene model, glTF/OBJ loaders, GLB writer, procedural meshes, ray caster",
      "Embree 3, tinygltf, tinyobjloader")],
    [("prt/", "prt::prt", "engine runtime: coefficient files of every kind, float16, lighting, relight kernels, haar/",
      "none (C++17)")],
    [("sh/", "prt::sh", "SH maths: basis, rotation, zonal convolution, windows, layouts, projection",
      "none (C++17)")],
]


def svg():
    width, box_h, gap, left = 900, 56, 22, 40
    height = len(LAYERS) * (box_h + gap) + 60
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="DejaVu Sans, sans-serif">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           '<defs><marker id="a" markerWidth="10" markerHeight="8" refX="9" refY="4" '
           'orient="auto"><path d="M0,0 L10,4 L0,8 z" fill="#555"/></marker></defs>',
           f'<text x="{left}" y="28" font-size="17" font-weight="bold">prt: each layer uses only '
           'the layers below it</text>']
    runtime = {"prt/", "sh/"}
    for i, row in enumerate(LAYERS):
        y = 44 + i * (box_h + gap)
        box_w = (width - 2 * left - (len(row) - 1) * gap) // len(row)
        for k, (folder, target, holds, libs) in enumerate(row):
            x0 = left + k * (box_w + gap)
            fill = "#e8f1fb" if folder in runtime else "#f5f5f5"
            out.append(f'<rect x="{x0}" y="{y}" width="{box_w}" height="{box_h}" rx="6" '
                       f'fill="{fill}" stroke="#4a6fa5" stroke-width="1.5"/>')
            out.append(f'<text x="{x0 + 14}" y="{y + 23}" font-size="15" font-weight="bold">'
                       f'{folder}  <tspan font-weight="normal" fill="#4a6fa5">{target}</tspan></text>')
            out.append(f'<text x="{x0 + 14}" y="{y + 44}" font-size="12.5">{holds}</text>')
            out.append(f'<text x="{x0 + box_w - 14}" y="{y + 23}" font-size="12" '
                       f'text-anchor="end" fill="#8a4b08">{libs}</text>')
        if i + 1 < len(LAYERS):
            x = width // 2
            out.append(f'<line x1="{x}" y1="{y + box_h}" x2="{x}" y2="{y + box_h + gap - 2}" '
                       'stroke="#555" stroke-width="1.5" marker-end="url(#a)"/>')
    out.append(f'<text x="{left}" y="{height - 10}" font-size="12" fill="#4a6fa5">Blue: the '
               'runtime libraries engines link (find_package(prt)); no third-party dependencies.'
               '</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    target = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else root / "docs/images/architecture.svg"
    target.write_text(svg())
    print(target)


if __name__ == "__main__":
    main()
