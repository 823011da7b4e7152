#!/usr/bin/env python3
"""SMUG `smug p2p` vs OMPL LazyPRMstar (`ompl_p2p`), query by query, on MovingAI maps.

For each map it converts the MovingAI map with `smug worlds convert-movingai`, writes the
queries the way `smug bench p2p` picks them (N scenarios spread evenly over the .scen file,
cell centres in world metres, yaw 0), runs `smug p2p` (disc robot, yaw weight 0, exactly
the pipeline of `smug bench p2p`) and `ompl_p2p` on them, checks every returned path
against the exact disc-vs-blocked-squares semantic (continuously, not only at the
validators' 0.05 m steps), and prints one Markdown table per map plus a summary.

Standard library only. See README.md beside this file.
"""

import argparse
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT_MAPS = ["mapf/random-32-32-10", "mapf/random-32-32-20", "dao/arena2"]


# ------------------------------------------------------------------ MovingAI files

def read_movingai_map(path):
    """(width, height, blocked[row][col]) with row 0 at the top, as in the file."""
    lines = [l.rstrip("\r\n") for l in path.read_text().splitlines()]
    if lines[0].split() != ["type", "octile"]:
        sys.exit(f"{path}: expected `type octile`")
    width = height = None
    k = 1
    while lines[k].strip() != "map":
        key, value = lines[k].split()
        if key == "height":
            height = int(value)
        elif key == "width":
            width = int(value)
        k += 1
    rows = lines[k + 1:k + 1 + height]
    blocked = [[c not in ".GS" for c in row] for row in rows]
    return width, height, blocked


def read_scenarios(path):
    scen = []
    lines = path.read_text().splitlines()
    if lines[0].split() != ["version", "1"]:
        sys.exit(f"{path}: expected `version 1`")
    for line in lines[1:]:
        if not line.strip():
            continue
        f = line.rstrip("\r").split("\t")
        if len(f) != 9:
            f = line.split()
        scen.append({
            "start": (int(f[4]), int(f[5])),
            "goal": (int(f[6]), int(f[7])),
            "optimal": float(f[8]),
        })
    return scen


def find_scen(data, name):
    """`dir/stem` -> (map, scen); `a.map:b.scen` is taken as is."""
    if ":" in name:
        m, s = name.split(":", 1)
        return data / m, data / s
    base = name[:-4] if name.endswith(".map") else name
    m = data / f"{base}.map"
    for cand in (data / f"{base}.map.scen", data / f"{base}-random-1.scen", data / f"{base}.scen"):
        if cand.exists():
            return m, cand
    sys.exit(f"no scenario file for {name} under {data}")


def pick(scenarios, count):
    """What `smug bench p2p` picks: `count` scenarios spread evenly over the file."""
    count = min(count, len(scenarios))
    return [scenarios[i * len(scenarios) // max(count, 1)] for i in range(count)]


def to_world(cell, height, res):
    x, y = cell
    return ((x + 0.5) * res, (height - 1 - y + 0.5) * res)


# ------------------------------------------------------------------ exact path check

def point_box_dist(px, py, x0, y0, x1, y1):
    dx = max(x0 - px, 0.0, px - x1)
    dy = max(y0 - py, 0.0, py - y1)
    return math.hypot(dx, dy)


def seg_seg_dist(a, b, c, d):
    def cross(o, p, q):
        return (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])

    d1, d2, d3, d4 = cross(c, d, a), cross(c, d, b), cross(a, b, c), cross(a, b, d)
    if d1 * d2 < 0 and d3 * d4 < 0:
        return 0.0

    def pt_seg(p, s, e):
        vx, vy = e[0] - s[0], e[1] - s[1]
        L = vx * vx + vy * vy
        t = 0.0 if L == 0 else max(0.0, min(1.0, ((p[0] - s[0]) * vx + (p[1] - s[1]) * vy) / L))
        return math.hypot(p[0] - s[0] - t * vx, p[1] - s[1] - t * vy)

    return min(pt_seg(a, c, d), pt_seg(b, c, d), pt_seg(c, a, b), pt_seg(d, a, b))


def seg_box_dist(a, b, x0, y0, x1, y1):
    # Inside the box (an endpoint in it, or crossing it): distance 0.
    if point_box_dist(*a, x0, y0, x1, y1) == 0.0 or point_box_dist(*b, x0, y0, x1, y1) == 0.0:
        return 0.0
    corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    return min(seg_seg_dist(a, b, corners[i], corners[(i + 1) % 4]) for i in range(4))


def path_clearance(waypoints, blocked_grid, width, height, res, radius):
    """Smallest distance from the path (its straight segments) to a blocked square or
    to the map border, minus the radius: < 0 means the disc overlaps something."""
    worst = math.inf
    for p in waypoints:
        worst = min(worst, p[0] - radius, width * res - p[0] - radius, p[1] - radius, height * res - p[1] - radius)
    for a, b in zip(waypoints, waypoints[1:]):
        a, b = (a[0], a[1]), (b[0], b[1])
        lo_i = max(0, int(math.floor((min(a[0], b[0]) - radius) / res)))
        hi_i = min(width - 1, int(math.floor((max(a[0], b[0]) + radius) / res)))
        lo_j = max(0, int(math.floor((min(a[1], b[1]) - radius) / res)))
        hi_j = min(height - 1, int(math.floor((max(a[1], b[1]) + radius) / res)))
        for j in range(lo_j, hi_j + 1):
            row = blocked_grid[height - 1 - j]  # grid row j (bottom-up) = file row H-1-j
            for i in range(lo_i, hi_i + 1):
                if row[i]:
                    d = seg_box_dist(a, b, i * res, j * res, (i + 1) * res, (j + 1) * res)
                    worst = min(worst, d - radius)
    return worst


# ------------------------------------------------------------------ running

def run(cmd, log):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.monotonic()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    log.write("$ " + " ".join(str(c) for c in cmd) + "\n" + proc.stdout + proc.stderr
              + f"[exit {proc.returncode}, wall {wall:.2f} s, cpu {cpu:.2f} s]\n")
    log.flush()
    if proc.returncode not in (0, 1):
        sys.exit(f"failed ({proc.returncode}): {' '.join(map(str, cmd))}\n{proc.stderr}")
    return proc.stdout.strip(), wall, cpu


def compare_map(args, name, work, log):
    map_path, scen_path = find_scen(args.data, name)
    stem = map_path.stem
    width, height, blocked = read_movingai_map(map_path)
    picked = pick(read_scenarios(scen_path), args.scenarios)
    res = args.resolution
    yaml = work / f"{stem}.yaml"
    run([args.smug, "worlds", "convert-movingai", map_path, yaml, "--resolution", str(res)], log)
    queries = work / f"{stem}.queries.csv"
    with open(queries, "w") as f:
        f.write("sx,sy,syaw,gx,gy,gyaw\n")
        for s in picked:
            sx, sy = to_world(s["start"], height, res)
            gx, gy = to_world(s["goal"], height, res)
            f.write(f"{sx!r},{sy!r},0,{gx!r},{gy!r},0\n")
    radius = args.radius * res
    smug_json = work / f"{stem}.smug.json"
    smug_cmd = [args.smug, "p2p", "--map", yaml, "--queries", queries, "--validity", "clearance-2d",
                "--radius", repr(radius), "--set", "space.type=se2", "--set", "space.params.rotation_weight=0",
                "--set", "objective.type=path-length", "--set", "objective.params.rotation_weight=0"]
    for s in args.smug_set:
        smug_cmd += ["--set", s]
    smug_out, smug_wall, smug_cpu = run(smug_cmd + ["--out", smug_json], log)
    ompl_json = work / f"{stem}.ompl.json"
    ompl_cmd = [args.peer, "--map", yaml, "--queries", queries, "--radius", repr(radius), "--time", str(args.time),
                "--seed", str(args.seed), "--clock", args.clock, "--space", args.space, "--motion-resolution", str(args.motion_resolution)]
    if args.simplify:
        ompl_cmd.append("--simplify")
    if args.first:
        ompl_cmd.append("--first")
    ompl_out, ompl_wall, ompl_cpu = run(ompl_cmd + ["--out", ompl_json], log)
    smug = json.loads(smug_json.read_text())
    ompl = json.loads(ompl_json.read_text())
    print(f"  smug: {smug_out}\n  ompl: {ompl_out}", file=sys.stderr)

    rows = []
    for k, s in enumerate(picked):
        row = {"k": k, "optimal": s["optimal"] * res}
        for tag, result in (("smug", smug), ("ompl", ompl)):
            q = result["queries"][k]
            row[tag] = q
            if q["status"] == "exact":
                pts = q["waypoints"]
                sx, sy = to_world(s["start"], height, res)
                gx, gy = to_world(s["goal"], height, res)
                ends_ok = (math.hypot(pts[0][0] - sx, pts[0][1] - sy) < 1e-9
                           and math.hypot(pts[-1][0] - gx, pts[-1][1] - gy) < 1e-9)
                length = sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(pts, pts[1:]))
                row[tag + "_clear"] = path_clearance(pts, blocked, width, height, res, radius)
                row[tag + "_ends_ok"] = ends_ok
                row[tag + "_length_ok"] = abs(length - q["cost"]) <= 1e-6 * max(1.0, length)
        rows.append(row)
    return {"map": name, "stem": stem, "rows": rows, "smug": smug, "ompl": ompl,
            "smug_wall": smug_wall, "ompl_wall": ompl_wall, "smug_cpu": smug_cpu, "ompl_cpu": ompl_cpu, "queries": len(picked)}


def summarise(r, args):
    rows = r["rows"]
    n = len(rows)
    out = {}
    for tag in ("smug", "ompl"):
        solved = [x for x in rows if x[tag]["status"] == "exact"]
        ratios = [x[tag]["cost"] / x["optimal"] for x in solved if x["optimal"] > 0]
        out[tag] = {
            "solved": len(solved),
            "statuses": {},
            "ratio_mean": sum(ratios) / len(ratios) if ratios else math.nan,
            "ratio_pooled": (sum(x[tag]["cost"] for x in solved) / sum(x["optimal"] for x in solved)
                             if solved and sum(x["optimal"] for x in solved) > 0 else math.nan),
            "time_mean": sum(x[tag]["time_s"] for x in rows) / n,
            "time_median": sorted(x[tag]["time_s"] for x in rows)[n // 2],
            "total": r[tag]["total_time_s"],
            "process_cpu": r[tag + "_cpu"],
            "cpu_mean": (sum(x[tag]["cpu_s"] for x in rows) / n) if all("cpu_s" in x[tag] for x in rows) else None,
            "vertices": rows[-1][tag]["vertices"],
            "colliding": sum(1 for x in solved if x[tag + "_clear"] < -1e-9),
            "worst_clear": min((x[tag + "_clear"] for x in solved), default=math.nan),
            "bad_ends": sum(1 for x in solved if not x[tag + "_ends_ok"]),
            "bad_cost": sum(1 for x in solved if not x[tag + "_length_ok"]),
        }
        for x in rows:
            out[tag]["statuses"][x[tag]["status"]] = out[tag]["statuses"].get(x[tag]["status"], 0) + 1
    both = [x for x in rows if x["smug"]["status"] == "exact" and x["ompl"]["status"] == "exact"]
    tol = 1e-6
    out["both"] = len(both)
    out["smug_wins"] = sum(1 for x in both if x["smug"]["cost"] < x["ompl"]["cost"] * (1 - tol))
    out["ompl_wins"] = sum(1 for x in both if x["ompl"]["cost"] < x["smug"]["cost"] * (1 - tol))
    out["ties"] = len(both) - out["smug_wins"] - out["ompl_wins"]
    out["only_smug"] = out["smug"]["solved"] - len(both)
    out["only_ompl"] = out["ompl"]["solved"] - len(both)
    for tag in ("smug", "ompl"):
        ratios = [x[tag]["cost"] / x["optimal"] for x in both if x["optimal"] > 0]
        out[tag]["ratio_common"] = sum(ratios) / len(ratios) if ratios else math.nan
    return out


def fmt(v, digits=3):
    return "–" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.{digits}f}"


def table(r, s, args):
    n = r["queries"]
    S, O = s["smug"], s["ompl"]
    st = lambda d: ", ".join(f"{k} {v}" for k, v in sorted(d.items()))
    lines = [
        f"### {r['map']} ({n} scenarios, disc radius {args.radius} cell, OMPL {args.time} s/query ({args.clock} clock{', first solution' if args.first else ''}), space {args.space})",
        "",
        "| | SMUG `smug p2p` | OMPL LazyPRMstar |",
        "|---|---:|---:|",
        f"| solved (exact) | {S['solved']}/{n} | {O['solved']}/{n} |",
        f"| statuses | {st(S['statuses'])} | {st(O['statuses'])} |",
        f"| mean length / optimal octile (own solved) | {fmt(S['ratio_mean'], 4)} | {fmt(O['ratio_mean'], 4)} |",
        f"| Σ length / Σ optimal (own solved; `bench p2p`'s number) | {fmt(S['ratio_pooled'], 4)} | {fmt(O['ratio_pooled'], 4)} |",
        f"| mean length / optimal on the {s['both']} solved by both | {fmt(S['ratio_common'], 4)} | {fmt(O['ratio_common'], 4)} |",
        f"| wins on length (both solved; ties {s['ties']}) | {s['smug_wins']} | {s['ompl_wins']} |",
        f"| solved only by this one | {s['only_smug']} | {s['only_ompl']} |",
        f"| mean time per query (s) | {fmt(S['time_mean'], 4)} | {fmt(O['time_mean'], 4)} |",
        f"| median time per query (s) | {fmt(S['time_median'], 4)} | {fmt(O['time_median'], 4)} |",
        f"| mean CPU time per query (s) | – | {fmt(O['cpu_mean'], 4)} |",
        f"| total planning time, wall (s) | {fmt(S['total'], 2)} | {fmt(O['total'], 2)} |",
        f"| whole process CPU time incl. map loading (s) | {fmt(S['process_cpu'], 2)} | {fmt(O['process_cpu'], 2)} |",
        f"| roadmap vertices after the last query | {S['vertices']} | {O['vertices']} |",
        f"| paths overlapping an obstacle (exact continuous check) | {S['colliding']} | {O['colliding']} |",
        f"| smallest clearance − radius along paths (m) | {fmt(S['worst_clear'], 4)} | {fmt(O['worst_clear'], 4)} |",
    ]
    if S["bad_ends"] or O["bad_ends"] or S["bad_cost"] or O["bad_cost"]:
        lines.append(f"| paths with wrong ends / cost ≠ polyline length | {S['bad_ends']}/{S['bad_cost']} | "
                     f"{O['bad_ends']}/{O['bad_cost']} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("maps", nargs="*", default=DEFAULT_MAPS,
                    help="maps under --data as dir/stem (e.g. dao/arena2), or MAP:SCEN paths relative to it "
                         f"(default: {' '.join(DEFAULT_MAPS)})")
    smug_data = os.environ.get("SMUG_DATA")
    ap.add_argument("--data", type=Path, default=Path(smug_data) / "movingai" if smug_data else None,
                    required=not smug_data,
                    help="the MovingAI data folder (default: $SMUG_DATA/movingai, as `smug bench p2p`)")
    ap.add_argument("--smug", default=str(HERE.parent.parent / "target" / "release" / "smug"),
                    help="the smug binary (default: the workspace's target/release/smug)")
    ap.add_argument("--peer", default=str(HERE / "ompl_p2p"), help="the ompl_p2p binary")
    ap.add_argument("--scenarios", type=int, default=50)
    ap.add_argument("--radius", type=float, default=0.25, help="disc radius in cells")
    ap.add_argument("--resolution", type=float, default=1.0, help="metres per cell of the converted maps")
    ap.add_argument("--time", type=float, default=0.2, help="OMPL planning time per query, s")
    ap.add_argument("--clock", choices=["wall", "cpu"], default="wall",
                    help="what OMPL's --time budget measures (cpu: its thread's CPU time; steadier on a busy machine)")
    ap.add_argument("--seed", type=int, default=1, help="OMPL seed (SMUG's is its config's seed = 1)")
    ap.add_argument("--space", choices=["se2", "r2"], default="se2")
    ap.add_argument("--motion-resolution", type=float, default=0.05,
                    help="OMPL DiscreteMotionValidator step in metres (SMUG p2p's default 0.05)")
    ap.add_argument("--simplify", action="store_true", help="let OMPL shortcut/smooth its paths")
    ap.add_argument("--first", action="store_true",
                    help="OMPL stops at its first solution (within --time) instead of optimising until --time")
    ap.add_argument("--smug-set", action="append", default=[], metavar="KEY=VALUE",
                    help="extra `--set` for smug p2p (e.g. planner.params.shortcut=true)")
    ap.add_argument("--work", type=Path, help="keep maps, queries, results and the log here (default: a temp dir)")
    ap.add_argument("--out", type=Path, help="also write the Markdown report here")
    ap.add_argument("--json", type=Path, help="write per-query numbers here")
    args = ap.parse_args()
    if args.data is None:
        ap.error("no MovingAI data: pass --data DIR or set SMUG_DATA (see docs/benchmarks.md)")
    for exe in (args.smug, args.peer):
        if not os.access(exe, os.X_OK):
            sys.exit(f"{exe}: not an executable (see --smug / --peer, README.md)")
    work = args.work or Path(tempfile.mkdtemp(prefix="ompl-peer-"))
    work.mkdir(parents=True, exist_ok=True)
    report = ["# SMUG vs OMPL LazyPRMstar, query by query (MovingAI)", "",
              f"Disc radius {args.radius} cell, yaw weight 0, {args.scenarios} scenarios per map spread over the "
              f".scen file (as `smug bench p2p`), one roadmap per map for each planner. SMUG: `smug p2p` defaults "
              f"(LazyPRM*, stall rule, no time limit). OMPL {args.time} s per query ({args.clock} clock), seed {args.seed}, space "
              f"{args.space}, DiscreteMotionValidator step {args.motion_resolution} m"
              f"{', PathSimplifier' if args.simplify else ', no simplification'}"
              f"{', first solution only' if args.first else ''}. Lengths in cells "
              f"(resolution {args.resolution}); optimal = the .scen's 8-connected optimum (no corner cutting), "
              f"so any-angle paths can go below 1.", ""]
    summary = ["| map | solved SMUG / OMPL | length/opt SMUG / OMPL (own solved) | length/opt on common | "
               "wins SMUG / OMPL / ties | mean time/query SMUG / OMPL (s) |", "|---|---:|---:|---:|---:|---:|"]
    everything = []
    with open(work / "compare.log", "a") as log:
        for name in args.maps:
            print(f"{name} …", file=sys.stderr)
            r = compare_map(args, name, work, log)
            s = summarise(r, args)
            report.append(table(r, s, args))
            n = r["queries"]
            summary.append(
                f"| {r['stem']} | {s['smug']['solved']}/{n} / {s['ompl']['solved']}/{n} | "
                f"{fmt(s['smug']['ratio_mean'], 4)} / {fmt(s['ompl']['ratio_mean'], 4)} | "
                f"{fmt(s['smug']['ratio_common'], 4)} / {fmt(s['ompl']['ratio_common'], 4)} | "
                f"{s['smug_wins']} / {s['ompl_wins']} / {s['ties']} | "
                f"{fmt(s['smug']['time_mean'], 4)} / {fmt(s['ompl']['time_mean'], 4)} |")
            everything.append({"map": name, "summary": s, "queries": [
                {"k": x["k"], "optimal": x["optimal"],
                 **{f"{t}_{f}": x[t][f] for t in ("smug", "ompl") for f in ("status", "cost", "time_s", "vertices")},
                 **{f"{t}_clearance": x.get(t + "_clear") for t in ("smug", "ompl")}} for x in r["rows"]]})
    report += ["### Summary", ""] + summary + ["", f"(work files: {work})", ""]
    text = "\n".join(report)
    print(text)
    if args.out:
        args.out.write_text(text)
    if args.json:
        args.json.write_text(json.dumps(everything, indent=1))


if __name__ == "__main__":
    main()
