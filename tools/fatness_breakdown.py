#!/usr/bin/env python3
"""Where a shell set's area-weighted fatness is lost, by triangle class.

Reads the output directory of `dcshell shell` (report.json and the shell_NNN.obj it names) and
sorts every triangle by where it lies -- on one of its shell's cut planes ("cut"), touching one
with a corner ("hull@cut"), or neither ("hull") -- and by shape: fat (fatness >= 0.2), or thin:
a needle (shortest / longest edge < 0.25), a cap (an angle above 2.2 rad) or other. Per class:
its share of the area, its fatness, its count, and its share of the deficit against 0.5 (the
equilateral value), i.e. how much the whole set would gain if that class became equilateral.

    python3 tools/fatness_breakdown.py SHELL_DIR
"""
import json
import math
import os
import sys


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


def read_obj(path):
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                verts.append([float(x) for x in p[1:4]])
            elif p[0] == "f":
                faces.append([int(x.split("/")[0]) - 1 for x in p[1:4]])
    return verts, faces


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: fatness_breakdown.py SHELL_DIR (the --out directory of dcshell shell)")
    root = sys.argv[1]
    report = json.load(open(os.path.join(root, "report.json")))
    total_area = total_fa = 0.0
    classes = {}
    for shell in report["shells"]:
        path = shell["file"] if os.path.isabs(shell["file"]) else os.path.join(root, os.path.basename(shell["file"]))
        verts, faces = read_obj(path)
        planes = shell["cut_planes"]

        # A corner is on a plane within a relative 1e-7: remeshing domes cut faces by ~1e-9.
        def on(c, x):
            return abs(dot(c["normal"], x) - c["offset"]) <= 1e-7 * (1 + abs(c["offset"]))

        for f in faces:
            P = [verts[i] for i in f]
            area = norm(cross(sub(P[1], P[0]), sub(P[2], P[0]))) / 2
            if area == 0:
                continue
            edges = [norm(sub(P[(k + 1) % 3], P[k])) for k in range(3)]
            angles = []
            for k in range(3):
                u, w = sub(P[(k + 1) % 3], P[k]), sub(P[(k + 2) % 3], P[k])
                angles.append(math.acos(max(-1.0, min(1.0, dot(u, w) / (norm(u) * norm(w))))))
            fat = sum(math.cos(a) for a in angles) - 1
            total_area += area
            total_fa += area * fat
            where = ("cut" if any(all(on(c, x) for x in P) for c in planes)
                     else "hull@cut" if any(any(on(c, x) for x in P) for c in planes) else "hull")
            if fat >= 0.2:
                shape = "fat"
            elif min(edges) / max(edges) < 0.25:
                shape = "thin needle"
            elif max(angles) > 2.2:
                shape = "thin cap"
            else:
                shape = "thin other"
            c = classes.setdefault((where, shape), [0.0, 0.0, 0])
            c[0] += area
            c[1] += area * fat
            c[2] += 1
    print("shells %d, area-weighted fatness %.4f" % (len(report["shells"]), total_fa / total_area))
    print("| where | shape | area | fatness | triangles | deficit share |")
    print("|---|---|---|---|---|---|")
    for (where, shape), (a, fa, n) in sorted(classes.items()):
        print("| %s | %s | %.1f%% | %.3f | %d | %.4f |" % (where, shape, 100 * a / total_area, fa / a, n,
                                                     (0.5 * a - fa) / total_area))


if __name__ == "__main__":
    main()
