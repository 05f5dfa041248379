#!/usr/bin/env python3
"""Seed 001's Table 2 for the spiral globe: managing a large texture with the texture quadtree.

Flies two paths over the Landsat 9 Kanto scene (a smooth pan at 8 km and a zoom from 400 km to
2 km over Tokyo) at 600^2, 800^2 and 1000^2 with `tellus bench --algo spiral --spiral-imagery`,
once with no cap on texture transfers and once with the seed's one transfer per update, and
prints frame ms, CPU ms, CPU idle and the texture update's mean and max (ms: reading the occlusion
counts, deciding, transferring; the render thread's wall time, FrameStats::textureUpdateMs).

  scripts/spiral_table2.py TELLUS STORE --imagery LANDSAT.tif [--geoid GTX] [--frames N] [--out DIR]

Frames end with glFinish (bench --finish). Every run's JSON report goes to DIR.
"""
import argparse
import json
import math
import pathlib

from spiral_tables import run_spiral_bench

SIZES = [1000, 800, 600]


def smooth_path(frames):
    # A pan across central Tokyo at 8 km, looking ahead and down.
    keys = []
    for k in range(frames):
        t = k / (frames - 1)
        keys.append({"time": float(k), "lat": 35.45 + 0.35 * t, "lon": 139.45 + 0.6 * t,
                     "alt": 8000.0, "heading": 50.0, "pitch": -45.0, "fov": 50.0})
    return {"keyframes": keys}


def zoom_path(frames):
    # Straight down on Tokyo station, from 400 km to 2 km (exponential in altitude).
    keys = []
    for k in range(frames):
        t = k / (frames - 1)
        keys.append({"time": float(k), "lat": 35.681, "lon": 139.767,
                     "alt": 400000.0 * math.pow(2000.0 / 400000.0, t), "heading": 0.0,
                     "pitch": -90.0 + 30.0 * t, "fov": 50.0})
    return {"keyframes": keys}


def bench(args, name, path, size, transfers):
    return run_spiral_bench(args, name, path, 2,
                            ["--size", f"{size}x{size}", "--spiral-imagery", args.imagery,
                             "--spiral-imagery-transfers", str(transfers)])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("tellus")
    parser.add_argument("store")
    parser.add_argument("--imagery", required=True, help="the Landsat 9 Kanto GeoTIFF")
    parser.add_argument("--geoid")
    parser.add_argument("--frames", type=int, default=60)
    parser.add_argument("--out", default="spiral-table2")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    paths = {}
    for name, make in (("smooth", smooth_path), ("zoom", zoom_path)):
        paths[name] = out / f"{name}-path.json"
        paths[name].write_text(json.dumps(make(args.frames)))

    print("Table 2 (medians; update mean and max over the path):\n")
    print("| size and path | frame ms | CPU ms | CPU idle | avg update ms "
          "| max update ms (no cap / one transfer) |")
    print("|---|---:|---:|---:|---:|---:|")
    for path in ("smooth", "zoom"):
        for size in SIZES:
            free = bench(args, f"{path}-{size}-nocap", paths[path], size, 0)
            one = bench(args, f"{path}-{size}-one", paths[path], size, 1)
            frame = one["frame_ms_median"]
            cpu = one["cpu_ms_median"]
            idle = max(0.0, 1.0 - cpu / frame) if frame > 0 else 0.0
            print(f"| {size}x{size} {path} | {frame:.1f} | {cpu:.1f} | {100 * idle:.0f}% "
                  f"| {one.get('texture_update_ms_mean', 0):.2f} "
                  f"| {free.get('texture_update_ms_max', 0):.1f} / "
                  f"{one.get('texture_update_ms_max', 0):.1f} |", flush=True)


if __name__ == "__main__":
    main()
