#!/usr/bin/python3
"""Render-thread CPU of streaming renderers, split as seed 002's Table 2: frames "inside a
block" (no streaming work reached the frame: nothing uploaded, loaded or rebuilt in the
background) and frames "crossing" (the others), from `tellus bench --csv` files.

usage: streaming_cpu_table.py BENCH.csv [BENCH.csv ...]   (prints a Markdown table)

render-thread CPU = the renderer's prepare() (CPU LOD: LOD, culling, reorganisation hand-off,
uploads), the render thread's own CPU clock (cpu_lod_thread_ms; wall-clock cpu_lod_ms where a
CSV lacks it, which also counts the time the thread was preempted); effective FPS = 1000 / its
median, as the seed defines it; background CPU = the worker threads' CPU per frame (loads,
reorganisation, copies).
"""
import csv
import statistics
import sys


def quantile(values, q):
    if not values:
        return float("nan")
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("| file | renderer | frames inside / crossing | render thread inside: median, max (ms) "
          "| effective FPS inside | render thread crossing: median, p99, max (ms) | frames over 1 ms "
          "| background CPU while crossing: median, max (ms) | triangles (median) |")
    print("|---|---|---|---|---:|---|---:|---|---:|")
    for path in sys.argv[1:]:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        for algo in dict.fromkeys(r["algo"] for r in rows):
            frames = [r for r in rows if r["algo"] == algo]
            quiet = lambda r: (int(r["tiles_loaded"]) == 0 and int(r.get("upload_bytes", 0)) == 0
                               and float(r["background_cpu_ms"]) == 0.0)
            key = "cpu_lod_thread_ms" if "cpu_lod_thread_ms" in frames[0] else "cpu_lod_ms"
            inside = [float(r[key]) for r in frames if quiet(r)]
            crossing = [float(r[key]) for r in frames if not quiet(r)]
            background = [float(r["background_cpu_ms"]) for r in frames if not quiet(r)]
            median_inside = statistics.median(inside) if inside else float("nan")
            print(f"| {path} | {algo} | {len(inside)} / {len(crossing)} "
                  f"| {median_inside:.3f}, {max(inside, default=float('nan')):.3f} "
                  f"| {1000.0 / median_inside:,.0f} "
                  f"| {statistics.median(crossing) if crossing else float('nan'):.3f}, "
                  f"{quantile(crossing, 0.99):.3f}, {max(crossing, default=float('nan')):.3f} "
                  f"| {sum(1 for v in crossing if v > 1.0)} "
                  f"| {statistics.median(background) if background else float('nan'):.1f}, "
                  f"{max(background, default=float('nan')):.1f} "
                  f"| {statistics.median(int(r['triangles']) for r in frames):,.0f} |")


if __name__ == "__main__":
    main()
