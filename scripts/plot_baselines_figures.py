#!/usr/bin/python3
"""Figures of scripts/baselines-figures.sh (docs/baselines.md):
  roam_target.png: ROAM's triangles and SSE p99 against its error target;
  cpu_motion.png: ROAM's CPU a frame (re-prioritising, splitting/merging, building the mesh) and
  the clipmaps' texture update against the camera's motion a frame;
and a Markdown table of each (roam_target.md, cpu_motion.md).

usage: plot_baselines_figures.py OUTPUT_FOLDER --targets PX=REPORT.json... --motion REPORT.json...
(Debian's python3-matplotlib)
"""
import json
import math
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    with open(path) as f:
        return json.load(f)


def algo_of(report, name):
    return next(a for a in report["algorithms"] if a["algo"] == name)


def metres_per_frame(algo):
    cams = [tuple(float(x) for x in f["camera"].split(",")[:3]) for f in algo["frames"]]
    steps = [math.dist(a, b) for a, b in zip(cams, cams[1:])]
    return statistics.median(steps) if steps else 0.0


def target_figure(folder, runs):
    rows = []
    for label, path in runs:
        s = algo_of(load(path), "roam")["summary"]
        rows.append((float(label), s["triangles_median"], s["sse_px_p95"], s["sse_px_p99"],
                     s["cpu_lod_ms_median"], s.get("lod_priority_ms_median", 0.0),
                     s.get("lod_refine_ms_median", 0.0), s.get("mesh_build_ms_median", 0.0),
                     s["crack_pixels_total"], s["pop_px_p99"]))
    rows.sort()
    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=110)
    ax.plot([r[0] for r in rows], [r[1] for r in rows], "o-", label="triangles (median)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("ROAM error target (px)")
    ax.set_ylabel("triangles per frame")
    ax2 = ax.twinx()
    ax2.plot([r[0] for r in rows], [r[3] for r in rows], "s--", color="tab:red", label="SSE p99 (px)")
    ax2.set_ylabel("measured SSE p99 (px)", color="tab:red")
    ax.set_title("ROAM: triangles and measured error against the error target", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    fig.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "roam_target.png"))
    plt.close(fig)
    with open(os.path.join(folder, "roam_target.md"), "w") as f:
        f.write("| target px | triangles | SSE p95 px | SSE p99 px | CPU LOD ms | priorities ms | "
                "splits/merges ms | mesh build ms | crack px | popping p99 px |\n")
        f.write("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
        for r in rows:
            f.write(f"| {r[0]:g} | {r[1]:,.0f} | {r[2]:.2f} | {r[3]:.2f} | {r[4]:.2f} | {r[5]:.2f} | "
                    f"{r[6]:.2f} | {r[7]:.2f} | {r[8]} | {r[9]:.2f} |\n")


def motion_figure(folder, paths):
    rows = []
    for path in paths:
        report = load(path)
        roam, clip = algo_of(report, "roam"), algo_of(report, "clipmaps")
        rs, cs = roam["summary"], clip["summary"]
        rows.append((metres_per_frame(roam), report["frames"], rs["cpu_lod_ms_median"],
                     rs.get("lod_priority_ms_median", 0.0), rs.get("lod_refine_ms_median", 0.0),
                     rs.get("mesh_build_ms_median", 0.0), rs["triangles_median"],
                     cs.get("texture_update_ms_median", 0.0), cs["cpu_lod_thread_ms_median"],
                     cs["triangles_median"], rs["cpu_lod_thread_ms_median"]))
    rows.sort()
    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=110)
    xs = [r[0] for r in rows]
    ax.plot(xs, [r[2] for r in rows], "o-", label="ROAM: prepare (priorities + splits/merges)")
    ax.plot(xs, [r[3] for r in rows], "o:", label="ROAM: re-prioritising")
    ax.plot(xs, [r[4] for r in rows], "o--", label="ROAM: splits and merges")
    ax.plot(xs, [r[5] for r in rows], "^-", label="ROAM: mesh built and uploaded")
    ax.plot(xs, [r[8] for r in rows], "s-", label="clipmaps: prepare (update + culling), thread CPU")
    ax.plot(xs, [r[7] for r in rows], "s:", label="clipmaps: texture update, wall (driver waits included)")
    ax.axhline(2.0, color="grey", linewidth=0.8, linestyle="--")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("camera motion a frame (m, median)")
    ax.set_ylabel("CPU ms per frame (median)")
    ax.set_title("CPU a frame against the camera's motion a frame (Korea flyover sampled at "
                 + ", ".join(str(r[1]) for r in rows) + " frames)", fontsize=8)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "cpu_motion.png"))
    plt.close(fig)
    with open(os.path.join(folder, "cpu_motion.md"), "w") as f:
        f.write("| frames | m a frame | ROAM prepare ms | thread CPU ms | priorities ms | splits/merges ms | "
                "mesh build ms | ROAM triangles | clipmaps update ms (wall) | clipmaps prepare ms (thread CPU) | clipmaps triangles |\n")
        f.write("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
        for r in sorted(rows, key=lambda r: r[1]):
            f.write(f"| {r[1]} | {r[0]:.0f} | {r[2]:.2f} | {r[10]:.2f} | {r[3]:.2f} | {r[4]:.2f} | {r[5]:.2f} | "
                    f"{r[6]:,.0f} | {r[7]:.2f} | {r[8]:.2f} | {r[9]:,.0f} |\n")


def main(argv):
    if len(argv) < 3 or "--targets" not in argv or "--motion" not in argv:
        sys.exit(__doc__)
    folder = argv[1]
    t, m = argv.index("--targets"), argv.index("--motion")
    targets = [a.split("=", 1) for a in argv[t + 1:m]]
    motion = argv[m + 1:]
    target_figure(folder, targets)
    motion_figure(folder, motion)


if __name__ == "__main__":
    main(sys.argv)
