# Baseline for issue #5 section 6: unfold meshes with Blender's bundled "Export Paper Model"
# add-on (io_export_paper_model) and measure what it produces, per mesh: islands (pieces), total
# cut length, overlaps, time. A dev tool, not part of the test suite; docs: doc/unfold_blender.md.
#
#   blender -b --factory-startup --python tools/blender_paper_model.py -- \
#       --out results.jsonl [--no-overlap-check] MESH.obj...
#
# One JSON object per mesh is appended to --out (JSON lines), written in two steps so that a
# driver that kills Blender (tools/run_blender_baseline.sh, `timeout`) still sees how far it got:
#   {"phase": "unfold", ...}   right after the add-on's unfolding (islands, cut length, time)
#   {"phase": "overlap", ...}  after our own overlap test of the islands (slow in pure Python)
#
# The add-on is called, never copied: we build its Unfolder on the imported object and call
# Unfolder.prepare() with the arguments ExportPaperModel.prepare() passes with default settings
# (default priority effects CONVEX 0.5 / CONCAVE 1 / LENGTH -0.05, limit_by_page False, scale 1),
# i.e. exactly the islands a user's "Export Paper Model" would write, without writing the PDF.
import argparse
import json
import math
import sys
import time

import addon_utils
import bpy


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="blender_paper_model.py")
    ap.add_argument("--out", required=True, help="JSON-lines file to append results to")
    ap.add_argument("--no-overlap-check", action="store_true", help="skip our own overlap test")
    ap.add_argument("--dump-cuts", action="store_true",
                    help="also record the cut edges (vertex index pairs) and the vertex coordinates, "
                         "for the edge-by-edge comparison in run_blender_baseline.py --edge-analysis")
    ap.add_argument("meshes", nargs="+")
    return ap.parse_args(argv)


def emit(path, record):
    # Append and flush at once: the process may be killed by the driver's timeout.
    with open(path, "a") as f:
        f.write(json.dumps(record) + "\n")


def clear_scene():
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for me in list(bpy.data.meshes):
        bpy.data.meshes.remove(me)


def import_obj(path, scale):
    # forward Y / up Z: keep the file's coordinates (Blender's default would rotate by 90 degrees;
    # harmless for lengths, but the identity keeps the numbers comparable with the file).
    bpy.ops.wm.obj_import(filepath=path, forward_axis='Y', up_axis='Z', global_scale=scale)
    obs = [ob for ob in bpy.context.selected_objects if ob.type == 'MESH']
    if len(obs) != 1:
        raise RuntimeError(f"{path}: expected one mesh object, got {len(obs)}")
    ob = obs[0]
    bpy.context.view_layer.objects.active = ob
    return ob


def run_addon(pm, ob):
    """The add-on's unfolding as ExportPaperModel.prepare() does it (object in edit mode)."""
    bpy.ops.object.mode_set(mode='EDIT')
    sce = bpy.context.scene
    unfolder = pm.Unfolder(ob)  # also runs its check_correct(): raises UnfoldError on bad geometry
    cage_size = pm.M.Vector((sce.paper_model.output_size_x, sce.paper_model.output_size_y))
    unfolder.prepare(cage_size, scale=sce.unit_settings.scale_length / 1.0,
                     limit_by_page=sce.paper_model.limit_by_page)
    return unfolder


def cut_stats(unfolder, scale):
    """Cut edges: edges with two faces whose faces are not joined in an island (is_main_cut).
    Each mesh edge is counted once. Edges with one face (open mesh) or more than two are counted
    apart: the inputs are closed 2-manifolds, so both counts should be 0."""
    mesh = unfolder.mesh
    m = mesh.matrix
    cut_len, cut_n, folded_n, odd_n = 0.0, 0, 0, 0
    for bmedge, edge in mesh.edges.items():
        if len(bmedge.link_faces) != 2:
            odd_n += 1
        if not edge.main_faces:
            continue
        if edge.is_main_cut:
            v = m @ edge.vector
            cut_len += math.sqrt(v.x * v.x + v.y * v.y + v.z * v.z)
            cut_n += 1
        else:
            folded_n += 1
    return cut_len / scale, cut_n, folded_n, odd_n


def island_triangles(island):
    """2D triangles of an island (fan of each face's loop order), as float tuples."""
    tris = []
    for face, uvface in island.faces.items():
        pts = [(uvface.vertices[loop].co.x, uvface.vertices[loop].co.y) for loop in face.loops]
        for i in range(1, len(pts) - 1):
            tris.append((pts[0], pts[i], pts[i + 1]))
    return tris


def penetration(t1, t2):
    """Separating-axis test of two triangles: the smallest overlap of their projections over the
    6 edge normals (<= 0: interior-disjoint; touching along an edge or at a point gives 0)."""
    depth = math.inf
    for tri in (t1, t2):
        for i in range(3):
            ax, ay = tri[i]
            bx, by = tri[(i + 1) % 3]
            nx, ny = ay - by, bx - ax
            n = math.hypot(nx, ny)
            if n == 0.0:
                continue
            nx, ny = nx / n, ny / n
            p1 = [x * nx + y * ny for x, y in t1]
            p2 = [x * nx + y * ny for x, y in t2]
            d = min(max(p1) - min(p2), max(p2) - min(p1))
            if d < depth:
                depth = d
                if depth <= 0.0:
                    return depth
    return depth


def overlap_check(islands, tol):
    """Our own overlap test, independent of the add-on's: every pair of triangles of the same
    island whose interiors overlap by more than tol (model units) is counted; a uniform grid
    on the triangles' boxes keeps it near linear. Islands are separate pieces of paper, so
    pairs from different islands never count. Returns (pairs, max depth)."""
    pairs, worst = 0, 0.0
    for island in islands:
        tris = island_triangles(island)
        if len(tris) < 2:
            continue
        boxes = [(min(p[0] for p in t), min(p[1] for p in t), max(p[0] for p in t), max(p[1] for p in t))
                 for t in tris]
        xs0, ys0 = min(b[0] for b in boxes), min(b[1] for b in boxes)
        xs1, ys1 = max(b[2] for b in boxes), max(b[3] for b in boxes)
        mean = sum(max(b[2] - b[0], b[3] - b[1]) for b in boxes) / len(boxes)
        cell = max(mean, (xs1 - xs0 + ys1 - ys0) * 1e-6, 1e-300)
        grid = {}
        for k, b in enumerate(boxes):
            for gx in range(int((b[0] - xs0) / cell), int((b[2] - xs0) / cell) + 1):
                for gy in range(int((b[1] - ys0) / cell), int((b[3] - ys0) / cell) + 1):
                    grid.setdefault((gx, gy), []).append(k)
        for (gx, gy), members in grid.items():
            for a in range(len(members)):
                i = members[a]
                bi = boxes[i]
                for c in range(a + 1, len(members)):
                    j = members[c]
                    bj = boxes[j]
                    lx, ly = max(bi[0], bj[0]), max(bi[1], bj[1])
                    if lx > min(bi[2], bj[2]) or ly > min(bi[3], bj[3]):
                        continue
                    # test each pair once: in the cell holding the low corner of the box overlap
                    if (int((lx - xs0) / cell), int((ly - ys0) / cell)) != (gx, gy):
                        continue
                    d = penetration(tris[i], tris[j])
                    if d > tol:
                        pairs += 1
                        worst = max(worst, d)
    return pairs, worst


def congruence(unfolder, scale):
    """How far the add-on's islands are from a true net of the mesh (rigid copies of its faces).
    The add-on merges island vertices closer than sqrt(1e-6 x edge length) (model units) when it
    joins two islands, so a gap left open around a curved vertex can be glued shut and the faces
    there deformed. Measured per face edge: |length in the island - length in 3D|; and the
    vertices that no cut reaches although the faces around them do not add up to 2 pi (a net
    can only close those by deforming its faces). Angles in doubles from the mesh's coordinates."""
    m = unfolder.mesh.matrix
    worst_rel, worst_abs = 0.0, 0.0
    for island in unfolder.mesh.islands:
        for face, uvface in island.faces.items():
            loops = list(face.loops)
            for i, loop in enumerate(loops):
                nxt = loops[(i + 1) % len(loops)]
                l3 = (m @ (nxt.vert.co - loop.vert.co)).length
                l2 = (uvface.vertices[nxt].co - uvface.vertices[loop].co).length
                if l3 > 0.0:
                    worst_rel = max(worst_rel, abs(l2 - l3) / l3)
                worst_abs = max(worst_abs, abs(l2 - l3))
    closed, closed_max = 0, 0.0
    for bmvert in unfolder.mesh.data.verts:
        if any(unfolder.mesh.edges[e].is_main_cut or not unfolder.mesh.edges[e].main_faces
               for e in bmvert.link_edges):
            continue
        total = 0.0
        for loop in bmvert.link_loops:
            # differences in doubles: mathutils computes in single precision
            p, u, w = ([float(x) for x in m @ l.vert.co]
                       for l in (loop, loop.link_loop_prev, loop.link_loop_next))
            a = [x - y for x, y in zip(u, p)]
            b = [x - y for x, y in zip(w, p)]
            dot = sum(x * y for x, y in zip(a, b))
            cr = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
            total += math.atan2(math.sqrt(sum(x * x for x in cr)), dot)
        deficit = abs(2.0 * math.pi - total)
        if deficit > 1e-5:  # above the angles' rounding from single-precision coordinates
            closed += 1
            closed_max = max(closed_max, deficit)
    return {"max_edge_error_rel": worst_rel, "max_edge_error": worst_abs / scale,
            "closed_curved_vertices": closed, "closed_max_deficit_rad": closed_max}


def bbox_diagonal(ob):
    xs = [v.co for v in ob.data.vertices]
    lo = [min(c[i] for c in xs) for i in range(3)]
    hi = [max(c[i] for c in xs) for i in range(3)]
    return math.dist(lo, hi)


def process(pm, path, args):
    rec = {"mesh": path}
    # The add-on refuses meshes with an edge shorter than 1e-6 or a face smaller than 1e-6 (in
    # its own units, regardless of the model's size): "zero-length edge(s) / zero-area face(s) ...
    # Export failed". Small models (the Cow parts, ~1 unit wide) trip it, so we retry at 10x, 100x,
    # ... as a user would scale the model up, and lengths are divided back by the factor. The
    # add-on is not scale-free: it merges island vertices closer than sqrt(1e-6 x edge length),
    # a tolerance that grows relative to the model as the model shrinks (see congruence()).
    scale, first_error = 1.0, None
    while True:
        clear_scene()
        t0 = time.perf_counter()
        ob = import_obj(path, scale)
        t_import = time.perf_counter() - t0
        rec.update(faces=len(ob.data.polygons), vertices=len(ob.data.vertices),
                   edges=len(ob.data.edges))
        t0 = time.perf_counter()
        try:
            unfolder = run_addon(pm, ob)
            break
        except pm.UnfoldError as e:
            bpy.ops.object.mode_set(mode='OBJECT')
            msg = e.args[0].replace("\n", " ").strip()
            if first_error is None:
                first_error = msg
            if "zero-" not in msg or scale >= 1e6:
                rec.update(phase="unfold", status="error", error=msg, scale=scale)
                emit(args.out, rec)
                return
            scale *= 10.0
    t_unfold = time.perf_counter() - t0
    islands = unfolder.mesh.islands
    cut_len, cut_n, folded_n, odd_n = cut_stats(unfolder, scale)
    rec.update(phase="unfold", status="ok", scale=scale, native_error=first_error,
               islands=len(islands), island_faces=[len(i.faces) for i in islands],
               cut_length=cut_len, cut_edges=cut_n, folded_edges=folded_n, non_manifold_edges=odd_n,
               # islands where the add-on's fast sweepline hit a GeometryError and it fell back to
               # its brute-force one (the only overlap-related state it keeps; it prints nothing)
               unsafe_geometry_islands=sum(1 for i in islands if not i.has_safe_geometry),
               import_s=t_import, unfold_s=t_unfold, **congruence(unfolder, scale))
    if args.dump_cuts:
        m = unfolder.mesh.matrix
        rec["cut_edge_vertices"] = sorted(sorted((e.va.index, e.vb.index)) for e in unfolder.mesh.edges.values()
                                          if e.main_faces and e.is_main_cut)
        rec["vertex_coords"] = [list(m @ v.co / scale) for v in unfolder.mesh.data.verts]
    emit(args.out, rec)
    if args.no_overlap_check:
        return
    # Blender stores coordinates in single precision: tolerance 1e-6 of the model size.
    diag = bbox_diagonal(ob)  # in scaled units, like the islands
    t0 = time.perf_counter()
    pairs, worst = overlap_check(islands, 1e-6 * diag)
    emit(args.out, {"mesh": path, "phase": "overlap", "overlap_pairs": pairs,
                    "overlap_max_depth": worst / scale, "overlap_max_depth_rel": worst / diag,
                    "check_s": time.perf_counter() - t0})
    del unfolder
    bpy.ops.object.mode_set(mode='OBJECT')


def main():
    args = parse_args()
    mod = addon_utils.enable("io_export_paper_model", default_set=True)
    if mod is None:
        emit(args.out, {"phase": "setup", "status": "error", "error": "add-on io_export_paper_model not found"})
        sys.exit(3)
    import io_export_paper_model as pm
    emit(args.out, {"phase": "setup", "blender": bpy.app.version_string,
                    "addon_version": ".".join(map(str, pm.bl_info["version"])), "addon_file": pm.__file__,
                    "priority_effect": pm.default_priority_effect,
                    "limit_by_page": bpy.context.scene.paper_model.limit_by_page})
    for path in args.meshes:
        process(pm, path, args)


main()
