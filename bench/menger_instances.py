#!/usr/bin/env python3
# Lucerna benchmark input (issue 14, instancing memory): writes a level-k Menger sponge as one
# cube object (12 triangles) placed 20^k times with ObjectInstance; level 5 = 3.2 M instances.
# Not a test: docs/benchmarks.md ("Object instancing") has the commands and the measurements.
import argparse
import sys


def sponge_cells(level):
    """Integer corners (x, y, z) of the 20^level cubes of side 1 in [0, 3^level)^3."""
    cells = [(0, 0, 0)]
    for _ in range(level):
        nxt = []
        for (x, y, z) in cells:
            for i in range(3):
                for j in range(3):
                    for k in range(3):
                        # Drop the centre and the face centres (two or more middle coordinates).
                        if (i == 1) + (j == 1) + (k == 1) >= 2:
                            continue
                        nxt.append((3 * x + i, 3 * y + j, 3 * z + k))
        cells = nxt
    return cells


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--level", type=int, default=5, help="sponge level: 20^level instances (default 5: 3.2 M)")
    ap.add_argument("-o", "--output", default="-", help="output .pbrt file (default stdout)")
    a = ap.parse_args()
    n = 3 ** a.level
    out = sys.stdout if a.output == "-" else open(a.output, "w")
    w = out.write
    w("# Menger sponge, level %d: %d instances of one cube (bench/menger_instances.py)\n" % (a.level, 20 ** a.level))
    w('LookAt 2.2 -3.0 1.8  0 0 0  0 0 1\nCamera "perspective" "float fov" 35\n')
    w('Film "rgb" "integer xresolution" 64 "integer yresolution" 64 "string filename" "menger.exr"\n')
    w('Sampler "independent" "integer pixelsamples" 1\n')
    w("WorldBegin\n")
    w('LightSource "distant" "point3 from" [1 -2 3] "point3 to" [0 0 0] "rgb L" [3 3 3]\n')
    w('LightSource "infinite" "rgb L" [0.2 0.2 0.25]\n')
    w('ObjectBegin "cube"\nMaterial "diffuse" "rgb reflectance" [0.7 0.6 0.5]\n')
    w('Shape "trianglemesh" "point3 P" [0 0 0  1 0 0  1 1 0  0 1 0  0 0 1  1 0 1  1 1 1  0 1 1]\n')
    w('  "integer indices" [0 2 1 0 3 2  4 5 6 4 6 7  0 1 5 0 5 4  1 2 6 1 6 5  2 3 7 2 7 6  3 0 4 3 4 7]\n')
    w("ObjectEnd\n")
    w("AttributeBegin\nScale %.9g %.9g %.9g\nTranslate %g %g %g\n" % (2.0 / n, 2.0 / n, 2.0 / n, -n / 2, -n / 2, -n / 2))
    for (x, y, z) in sponge_cells(a.level):
        w('AttributeBegin Translate %d %d %d ObjectInstance "cube" AttributeEnd\n' % (x, y, z))
    w("AttributeEnd\n")
    if out is not sys.stdout:
        out.close()


if __name__ == "__main__":
    main()
