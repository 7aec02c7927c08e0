#!/usr/bin/env python3
"""Writes the small composite examples in data/ (run from the repository root).

`--large-spheres DIR` instead writes, outside the repository, the scaling case of doc/shell.md:
two overlapping UV spheres of 24,864 and 1,512 faces (one part per file). `--deep-overlaps DIR`
writes the deep-overlap cases of doc/check.md: DIR/planks20 (twenty planks through one axis),
DIR/boxes128 (128 randomly rotated boxes, seeded), DIR/spheres8 (eight 960-face spheres
around one point, seeded) and DIR/chain100 (a hundred 960-face spheres, each placed next to one
of the five before it, like the parts of a segmented organic model; seeded). `--random-composites
DIR` writes the robustness set of doc/shell.md: DIR/m000 ... DIR/m119, each 2-13 randomly turned
boxes, UV spheres, prisms and needles (some duplicated, some with a shrunken copy nested inside),
at scales 1, 1e-4 or 1e3 and offsets up to 1e5, written with 12 significant digits (so faces that
were planar are not quite, as in files from other tools); seeded by the folder number.

Every example is a folder with one OBJ per part, except `snowman.obj`, whose connected
components are the parts. Coordinates are exact decimals so the files are reproducible.
"""
import math
import os
import random

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")


def box(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return v, f


def transform(mesh, angle_deg=0.0, shift=(0, 0, 0)):
    v, f = mesh
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)
    return [(round(c * x - s * y + shift[0], 12), round(s * x + c * y + shift[1], 12), round(z + shift[2], 12))
            for x, y, z in v], f


def sphere(center, r, n_lat=8, n_lon=12):
    v = [(center[0], center[1], center[2] + r)]
    for i in range(1, n_lat):
        th = math.pi * i / n_lat
        for j in range(n_lon):
            ph = 2 * math.pi * j / n_lon
            v.append(tuple(round(c + d, 12) for c, d in zip(center, (r * math.sin(th) * math.cos(ph),
                                                                       r * math.sin(th) * math.sin(ph),
                                                                       r * math.cos(th)))))
    v.append((center[0], center[1], center[2] - r))
    f = []
    for j in range(n_lon):
        f.append((0, 1 + j, 1 + (j + 1) % n_lon))
    for i in range(n_lat - 2):
        for j in range(n_lon):
            a = 1 + i * n_lon + j
            b = 1 + i * n_lon + (j + 1) % n_lon
            f.append((a, a + n_lon, b + n_lon))
            f.append((a, b + n_lon, b))
    last = len(v) - 1
    base = 1 + (n_lat - 2) * n_lon
    for j in range(n_lon):
        f.append((last, base + (j + 1) % n_lon, base + j))
    return v, f


def write(path, meshes, names=None):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as out:
        out.write("# dcshell example (tools/make_examples.py)\n")
        off = 1
        for k, (v, f) in enumerate(meshes):
            if names:
                out.write("o %s\n" % names[k])
            for p in v:
                out.write("v %.12g %.12g %.12g\n" % p)
            for face in f:
                out.write("f " + " ".join(str(i + off) for i in face) + "\n")
            off += len(v)


def large_spheres(out_dir):
    write(os.path.join(out_dir, "big.obj"), [sphere((0, 0, 0), 1.0, 112, 112)])
    write(os.path.join(out_dir, "small.obj"), [sphere((1.1, 0.2, 0.1), 0.6, 28, 28)])


def deep_overlaps(out_dir):
    plank = box((-4, -0.3, -0.05), (4, 0.3, 0.05))
    for k in range(20):
        write(os.path.join(out_dir, "planks20", "plank_%02d.obj" % k), [transform(plank, 9.0 * k, (0, 0, 0.001 * k))])
    rng = random.Random(128)
    for k in range(128):
        h = [rng.uniform(0.3, 1.5) for _ in range(3)]
        c = [rng.uniform(0, 8) for _ in range(3)]
        a, b = rng.uniform(0, 360), rng.uniform(0, 2 * math.pi)
        v, f = transform(box((-h[0], -h[1], -h[2]), (h[0], h[1], h[2])), a)
        # then a turn about x, and the move to the centre
        v = [(round(x + c[0], 12), round(math.cos(b) * y - math.sin(b) * z + c[1], 12),
              round(math.sin(b) * y + math.cos(b) * z + c[2], 12)) for x, y, z in v]
        write(os.path.join(out_dir, "boxes128", "box_%03d.obj" % k), [(v, f)])
    rng = random.Random(8)
    for k in range(8):
        c = tuple(rng.uniform(-0.3, 0.3) for _ in range(3))
        write(os.path.join(out_dir, "spheres8", "sphere_%d.obj" % k), [sphere(c, rng.uniform(0.8, 1.2), 16, 32)])
    rng = random.Random(100)
    centres = [(0.0, 0.0, 0.0)]
    while len(centres) < 100:
        p = rng.choice(centres[-5:])
        d = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in d))
        centres.append(tuple(round(a + 1.2 * x / n, 9) for a, x in zip(p, d)))
    for k, c in enumerate(centres):
        write(os.path.join(out_dir, "chain100", "sphere_%03d.obj" % k), [sphere(c, round(rng.uniform(0.6, 0.9), 9), 16, 32)])


def prism(r, h, n):
    """A right prism over a regular n-gon of radius r (a cylinder for large n), centred at 0."""
    v = []
    for i in range(n):
        a = 2 * math.pi * i / n
        v += [(r * math.cos(a), r * math.sin(a), -h / 2), (r * math.cos(a), r * math.sin(a), h / 2)]
    v += [(0, 0, -h / 2), (0, 0, h / 2)]
    f = []
    for i in range(n):
        j = (i + 1) % n
        f += [(2 * i, 2 * j, 2 * j + 1), (2 * i, 2 * j + 1, 2 * i + 1), (2 * n, 2 * j, 2 * i), (2 * n + 1, 2 * i + 1, 2 * j + 1)]
    return v, f


def turned(mesh, angles, shift, scale):
    """Scaled, turned about x, y and z in that order, then moved."""
    v, f = mesh
    out = []
    for p in v:
        x, y, z = (c * scale for c in p)
        for axis, a in enumerate(angles):
            c, s = math.cos(a), math.sin(a)
            if axis == 0:
                y, z = c * y - s * z, s * y + c * z
            elif axis == 1:
                x, z = c * x + s * z, -s * x + c * z
            else:
                x, y = c * x - s * y, s * x + c * y
        out.append((x + shift[0], y + shift[1], z + shift[2]))
    return out, f


def random_composites(out_dir, count=120):
    for m in range(count):
        rng = random.Random(m)
        scale = rng.choice([1, 1, 1e-4, 1e3])
        offset = rng.choice([0, 0, 1e5, -37.5])
        parts = []
        for _ in range(rng.randrange(2, 14)):
            kind = rng.randrange(4)
            if kind == 0:
                h = [rng.uniform(0.2, 2) for _ in range(3)]
                mesh = box((-h[0], -h[1], -h[2]), tuple(h))
            elif kind == 1:
                mesh = sphere((0, 0, 0), rng.uniform(0.3, 1.5), rng.randrange(3, 12), rng.randrange(4, 20))
            elif kind == 2:
                mesh = prism(rng.uniform(0.1, 1), rng.uniform(0.5, 4), rng.randrange(3, 30))
            else:  # a needle
                h = [rng.uniform(0.01, 0.3) for _ in range(2)]
                mesh = box((-h[0], -h[1], -3), (h[0], h[1], 3))
            shift = tuple(rng.uniform(-2, 2) * scale + offset for _ in range(3))
            angles = [rng.choice([0, rng.uniform(0, 6.3)]) for _ in range(3)]
            parts.append(turned(mesh, angles, shift, scale))
            r = rng.random()
            if r < 0.08:
                parts.append(parts[-1])
            elif r < 0.15:
                v, f = parts[-1]
                c = [sum(p[k] for p in v) / len(v) for k in range(3)]
                parts.append(([tuple(c[k] + 0.5 * (p[k] - c[k]) for k in range(3)) for p in v], f))
        for k, p in enumerate(parts):
            write(os.path.join(out_dir, "m%03d" % m, "p%02d.obj" % k), [p])


def main():
    # The paper's controlled study: two bars meeting at an elbow, at several angles.
    bar = box((-0.25, -2.0, -0.25), (0.25, 0.25, 0.25))
    for deg in (15, 30, 45, 60, 75, 90):
        d = os.path.join(ROOT, "bars", "bars_%02d" % deg)
        write(os.path.join(d, "bar_a.obj"), [bar])
        write(os.path.join(d, "bar_b.obj"), [transform(bar, 180 - deg)])
    # Three boxes overlapping in a common region.
    d = os.path.join(ROOT, "three_boxes")
    write(os.path.join(d, "box_a.obj"), [box((0, 0, 0), (2, 1, 1))])
    write(os.path.join(d, "box_b.obj"), [box((1, 0.25, 0.25), (2.5, 2, 1.25))])
    write(os.path.join(d, "box_c.obj"), [box((0.5, 0.5, -0.5), (1.75, 1.5, 0.75))])
    # A part nested inside another, next to a third that overlaps the container.
    d = os.path.join(ROOT, "nested")
    write(os.path.join(d, "outer.obj"), [box((0, 0, 0), (2, 2, 2))])
    write(os.path.join(d, "inner.obj"), [box((0.5, 0.5, 0.5), (1, 1, 1))])
    write(os.path.join(d, "side.obj"), [box((1.5, 0.5, 0.5), (3, 1.5, 1.5))])
    # A cube cut into pieces that share faces (already disjoint: no cut needed).
    d = os.path.join(ROOT, "split_cube")
    write(os.path.join(d, "left.obj"), [box((0, 0, 0), (0.5, 1, 1))])
    write(os.path.join(d, "right_front.obj"), [box((0.5, 0, 0), (1, 0.5, 1))])
    write(os.path.join(d, "right_back.obj"), [box((0.5, 0.5, 0), (1, 1, 1))])
    # A star of eight thin planks crossing through one vertical axis, each a little higher: every
    # pair overlaps, and each hull loses most of its volume to the other planes.
    plank = box((-4, -0.3, -0.05), (4, 0.3, 0.05))
    for k in range(8):
        write(os.path.join(ROOT, "plank_star", "plank_%d.obj" % k),
              [transform(plank, 22.5 * k, (0, 0, 0.01 * k))])
    # A snowman of three overlapping spheres in one file: its connected components are the parts.
    write(os.path.join(ROOT, "snowman.obj"),
          [sphere((0, 0, 0), 1.0), sphere((0, 0, 1.45), 0.7), sphere((0, 0, 2.4), 0.45)])


if __name__ == "__main__":
    import sys
    if len(sys.argv) == 3 and sys.argv[1] == "--large-spheres":
        large_spheres(sys.argv[2])
    elif len(sys.argv) == 3 and sys.argv[1] == "--deep-overlaps":
        deep_overlaps(sys.argv[2])
    elif len(sys.argv) == 3 and sys.argv[1] == "--random-composites":
        random_composites(sys.argv[2])
    elif len(sys.argv) == 1:
        main()
    else:
        sys.exit("usage: make_examples.py [--large-spheres DIR | --deep-overlaps DIR | --random-composites DIR]")
