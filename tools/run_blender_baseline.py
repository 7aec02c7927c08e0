#!/usr/bin/env python3
"""Issue #5 section 6: Blender's "Export Paper Model" add-on against `dcshell unfold`, per input.

Inputs: the issue's 69 (the 34 models of DATA/convex, the convex hulls of the parts of the
composite models Bulbasaur, Squirtle, Cow, written by build/tools/write_part_hulls). For each:
  - Blender: one process per mesh under `timeout` (default 120 s, the issue's limit; it includes
    Blender's ~1 s start-up), running tools/blender_paper_model.py (add-on defaults);
  - ours: `dcshell unfold --objective cut-length` (and hull-area), unfold.json read back.
Writes one CSV row per input (doc/data/blender_paper_model.csv). Work files go to --work
(outside the repository). Jobs run one at a time under `nice`: the machine is shared.

usage: tools/run_blender_baseline.py [--data ../shared/data] [--work /tmp/blender_baseline]
           [--csv doc/data/blender_paper_model.csv] [--timeout 120] [--repeat 1]
           [--only NAME,...] [--reuse-blender] [--no-hull-area]
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
COMPOSITES = ["Bulbasaur", "Squirtle", "Cow"]


def inputs(data, work):
    """(set, name, path) of the 69 inputs, convex models first, then the part hulls."""
    out = [("convex", p.stem, p) for p in sorted((data / "convex").glob("*.obj"))]
    hull_dir = work / "hulls"
    tool = ROOT / "build" / "tools" / "write_part_hulls"
    if not tool.exists():
        print(f"warning: {tool} not built: part hulls skipped", file=sys.stderr)
        return out
    subprocess.run([str(tool), "--out", str(hull_dir)] + [str(data / "composite" / m) for m in COMPOSITES],
                   check=True, stdout=subprocess.DEVNULL)
    for m in COMPOSITES:
        for p in sorted(hull_dir.glob(m + "__*.obj")):
            out.append(("hull:" + m, p.stem.split("__", 1)[1], p))
    return out


def run_blender(path, jsonl, timeout):
    """One Blender process for one mesh; returns (exit status, wall seconds). 124 = timed out."""
    cmd = ["timeout", str(timeout), "nice", "blender", "-b", "--factory-startup", "--python",
           str(ROOT / "tools" / "blender_paper_model.py"), "--", "--out", str(jsonl), str(path)]
    t0 = time.perf_counter()
    rc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
    return rc, time.perf_counter() - t0


def read_jsonl(jsonl, path):
    """The records of one mesh: (unfold, overlap, timed out)."""
    unfold, overlap, timed_out = None, None, False
    if jsonl.exists():
        for line in jsonl.read_text().splitlines():
            r = json.loads(line)
            if r.get("mesh") == str(path):
                if r["phase"] == "unfold":
                    unfold = r
                elif r["phase"] == "overlap":
                    overlap = r
                elif r["phase"] == "timeout":
                    timed_out = True
    return unfold, overlap, timed_out


def run_ours(path, objective, out_dir, repeat, timeout, extra=()):
    """`dcshell unfold` on one mesh; returns its unfold.json shell record (None: bad input or
    timed out) and the median wall time. The wall time includes the folding check, which
    unfold.json's unfold_time_s leaves out."""
    walls = []
    for _ in range(repeat):
        cmd = ["timeout", str(timeout), "nice", str(ROOT / "build" / "dcshell"), "unfold", "--objective", objective,
               *extra, "--force", "--out", str(out_dir), str(path)]
        t0 = time.perf_counter()
        rc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
        walls.append(time.perf_counter() - t0)
        if rc == 124:
            return "timeout", walls[-1]
        if rc == 2:
            return None, None
    shell = json.loads((out_dir / "unfold.json").read_text())["shells"][0]
    return shell, statistics.median(walls)


def read_obj(path):
    """Vertices and faces (0-based corner indices) of an OBJ file."""
    verts, faces = [], []
    for line in Path(path).read_text().splitlines():
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            verts.append(tuple(float(x) for x in t[1:4]))
        elif t[0] == "f":
            faces.append([int(c.split("/")[0]) - 1 for c in t[1:]])
    return verts, faces


def face_normal(verts, f):
    a, b, c = (verts[i] for i in f[:3])
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    ln = sum(x * x for x in n) ** 0.5
    return [x / ln for x in n]


def edge_analysis(path, net_obj, blender_rec):
    """Edge by edge: which mesh edges Blender cuts and which ours cuts (from our net: faces are in
    shell order, corners in shell order, and corners joined by a fold are one net vertex)."""
    import math
    verts, faces = read_obj(path)
    _, net_faces = read_obj(net_obj)
    assert len(net_faces) == len(faces), "net faces must be in shell order"
    sides = {}  # undirected edge -> list of (face, net edge)
    for k, (f, g) in enumerate(zip(faces, net_faces)):
        for i in range(len(f)):
            e = tuple(sorted((f[i], f[(i + 1) % len(f)])))
            sides.setdefault(e, []).append((k, frozenset((g[i], g[(i + 1) % len(g)]))))
    ours = {e for e, s in sides.items() if len(s) != 2 or s[0][1] != s[1][1]}
    # Blender's vertex indices are the file's (one object, no merging): checked on coordinates.
    bc = blender_rec["vertex_coords"]
    diag = math.dist([min(v[k] for v in verts) for k in range(3)], [max(v[k] for v in verts) for k in range(3)])
    assert len(bc) == len(verts) and max(math.dist(a, b) for a, b in zip(bc, verts)) < 1e-5 * diag
    blender = {tuple(e) for e in blender_rec["cut_edge_vertices"]}

    def length(e):
        return math.dist(verts[e[0]], verts[e[1]])

    def angle(e):  # dihedral (fold) angle in degrees
        (f1, _), (f2, _) = sides[e]
        n1, n2 = face_normal(verts, faces[f1]), face_normal(verts, faces[f2])
        return math.degrees(math.acos(max(-1.0, min(1.0, sum(a * b for a, b in zip(n1, n2))))))

    def summary(es):
        if not es:
            return "0"
        ls = sorted(length(e) for e in es)
        ang = sorted(angle(e) for e in es)
        return (f"{len(es)} edges, length {sum(ls):.4g} (median edge {ls[len(ls) // 2]:.3g}), "
                f"fold angle median {ang[len(ang) // 2]:.3g} deg")

    all_len = sorted(length(e) for e in sides)
    return {"blender_cut": summary(blender), "ours_cut": summary(ours),
            "both": summary(blender & ours), "only_blender": summary(blender - ours),
            "only_ours": summary(ours - blender),
            "mesh_edges": f"{len(sides)} edges, median length {all_len[len(all_len) // 2]:.3g}"}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", type=Path, default=ROOT.parent / "shared" / "data")
    ap.add_argument("--work", type=Path, default=Path("/tmp/blender_baseline"))
    ap.add_argument("--csv", type=Path, default=ROOT / "doc" / "data" / "blender_paper_model.csv")
    ap.add_argument("--timeout", type=int, default=120)
    ap.add_argument("--ours-timeout", type=int, default=180,
                    help="limit per `dcshell unfold` run (its folding check is slow on ball_large)")
    ap.add_argument("--repeat", type=int, default=1, help="runs of ours per input (median wall time)")
    ap.add_argument("--only", default="", help="comma-separated input names")
    ap.add_argument("--reuse-blender", action="store_true",
                    help="keep the Blender results already in WORK/blender.jsonl (rerun only missing ones)")
    ap.add_argument("--skip-ours", action="store_true", help="Blender only (e.g. while dcshell builds)")
    ap.add_argument("--edge-analysis", default="",
                    help="comma-separated input names: edge-by-edge comparison of the cuts (needs the "
                         "ours results in WORK from a previous run), printed as Markdown; no CSV")
    ap.add_argument("--no-hull-area", action="store_true", help="skip ours with --objective hull-area")
    ap.add_argument("--ours-arg", action="append", default=[],
                    help="extra option for dcshell unfold, repeatable (e.g. --ours-arg=--fold-descent-work=0)")
    args = ap.parse_args()

    args.work.mkdir(parents=True, exist_ok=True)
    jsonl = args.work / "blender.jsonl"
    only = set(filter(None, args.only.split(",")))
    if args.edge_analysis:
        wanted = args.edge_analysis.split(",")
        cuts = args.work / "blender_cuts.jsonl"
        for set_name, name, path in inputs(args.data, args.work):
            if name not in wanted:
                continue
            rec, _, _ = read_jsonl(cuts, path)
            if rec is None:
                subprocess.run(["timeout", str(args.timeout), "nice", "blender", "-b", "--factory-startup",
                                "--python", str(ROOT / "tools" / "blender_paper_model.py"), "--",
                                "--no-overlap-check", "--dump-cuts", "--out", str(cuts), str(path)],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                rec, _, _ = read_jsonl(cuts, path)
            if rec is None or rec["status"] != "ok":
                print(f"{name}: no Blender result")
                continue
            res = edge_analysis(path, args.work / "ours" / "cut-length" / name / "net_000.obj", rec)
            print(f"**{set_name} {name}** ({res['mesh_edges']}; Blender {rec['islands']} island(s))\n")
            for k in ("blender_cut", "ours_cut", "both", "only_blender", "only_ours"):
                print(f"- {k.replace('_', ' ')}: {res[k]}")
            print()
        return

    if not args.reuse_blender and jsonl.exists():
        jsonl.unlink()
    rows = []
    for set_name, name, path in inputs(args.data, args.work):
        if only and name not in only:
            continue
        row = {"set": set_name, "name": name}
        unfold, overlap, timed_out = read_jsonl(jsonl, path)
        rc, wall = None, None
        if unfold is None and not timed_out:
            rc, wall = run_blender(path, jsonl, args.timeout)
            if rc == 124:  # remembered for --reuse-blender
                with open(jsonl, "a") as f:
                    f.write(json.dumps({"mesh": str(path), "phase": "timeout", "timeout_s": args.timeout}) + "\n")
            unfold, overlap, timed_out = read_jsonl(jsonl, path)
        if unfold is None:
            row["blender_status"] = "timeout" if timed_out else f"failed(rc={rc})"
        else:
            row["blender_status"] = unfold["status"]
            row["faces"] = unfold["faces"]
            if unfold["status"] == "ok":
                row.update(blender_islands=unfold["islands"], blender_cut_length=unfold["cut_length"],
                           blender_cut_edges=unfold["cut_edges"], blender_scale=unfold["scale"],
                           blender_unsafe_geometry_islands=unfold["unsafe_geometry_islands"],
                           blender_unfold_s=unfold["unfold_s"],
                           blender_largest_island_faces=max(unfold["island_faces"]))
                for k in ("max_edge_error_rel", "max_edge_error", "closed_curved_vertices",
                          "closed_max_deficit_rad"):  # congruence of its islands (older runs: absent)
                    if k in unfold:
                        row["blender_" + k] = unfold[k]
                if unfold.get("native_error"):
                    row["blender_native_error"] = unfold["native_error"][:80]
            else:
                row["blender_native_error"] = unfold.get("error", "")[:80]
        if overlap is not None:
            row.update(blender_overlap_pairs=overlap["overlap_pairs"],
                       blender_overlap_max_depth_rel=overlap["overlap_max_depth_rel"])
        if wall is not None:
            row["blender_wall_s"] = wall

        for objective, key in (("cut-length", "ours_cut"), ("hull-area", "ours_hull")):
            if args.skip_ours or (objective == "hull-area" and args.no_hull_area):
                continue
            shell, wall = run_ours(path, objective, args.work / "ours" / objective / name, args.repeat,
                                   args.ours_timeout, args.ours_arg)
            if shell is None or shell == "timeout":
                row[key + "_status"] = "bad input" if shell is None else f"timeout({args.ours_timeout}s)"
                continue
            row[key + "_status"] = "ok"
            row.setdefault("faces", shell["faces"])
            row.update({key + "_cut_length": shell["cut_length"], key + "_hull_area": shell["hull_area"],
                        key + "_overlap_free": shell["overlap_free"],
                        key + "_fold_verified": shell["fold_path_verified"],
                        key + "_flat_angle": shell["flat_angle"],
                        key + "_unfold_s": shell["unfold_time_s"], key + "_wall_s": wall})
        if "blender_cut_length" in row and "ours_cut_cut_length" in row:
            row["ratio_cut"] = row["ours_cut_cut_length"] / row["blender_cut_length"]
        rows.append(row)
        print(set_name, name, row.get("faces"), row["blender_status"], row.get("blender_islands"),
              row.get("blender_cut_length"), row.get("blender_overlap_pairs"), row.get("blender_unfold_s"),
              row.get("ours_cut_cut_length"), row.get("ratio_cut"), flush=True)

    fields = []
    for r in rows:
        fields += [k for k in r if k not in fields]
    args.csv.parent.mkdir(parents=True, exist_ok=True)
    with open(args.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in r.items()})
    print("wrote", args.csv, len(rows), "rows", file=sys.stderr)


if __name__ == "__main__":
    main()
