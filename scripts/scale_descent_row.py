#!/usr/bin/env python3
"""One row of docs/scale.md's streaming table from a `tellus bench --json` report of one renderer
(scripts/scale-check.sh):

    scripts/scale_descent_row.py REPORT.json ALGO LABEL

Prints | renderer | served | frames | cracks | SSE p95 / p99 | frame ms median | slowest frame |
render-thread LOD ms max | GPU waits | tiles missed |. Exits 1 when a --quality report counted
crack pixels.
"""
import json
import statistics
import sys

report, algo, label = json.load(open(sys.argv[1])), sys.argv[2], sys.argv[3]
run = report["algorithms"][0]
rows, summary = run["frames"], run["summary"]
frame_ms = [f["frame_ms"] for f in rows]
quality = bool(report.get("quality"))
if quality:
    worst = max(f.get("crack_pixels", 0) for f in rows)
    cracks = f"{summary['crack_pixels_total']} ({worst})"
    sse = f"{summary['sse_px_p95']:.2f} / {summary['sse_px_p99']:.2f}"
else:
    cracks = sse = "not measured"
lod_max = max(f["cpu_lod_ms"] for f in rows)
waits = sum(f.get("gpu_waits", 0) for f in rows)
print(f"| {algo} | {label} | {len(rows)} | {cracks} | {sse} | {statistics.median(frame_ms):.1f} | "
      f"{max(frame_ms):.0f} | {lod_max:.2f} | {waits} | {summary['cache_misses_total']} |")
sys.exit(1 if quality and summary["crack_pixels_total"] else 0)
