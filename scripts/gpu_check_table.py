#!/usr/bin/env python3
"""The markdown table of scripts/gpu-check.sh: one row per renderer and bench run, from the
bench's JSON reports in a folder (NAME.json, in the order the script runs them).

    python3 scripts/gpu_check_table.py OUT_DIR > OUT_DIR/summary.md

Columns (medians over the frames unless said): frame ms (max of CPU LOD + submit and GPU),
the render thread's CPU ms (its own CPU clock over prepare and draw: what it spent, waiting
excluded; on llvmpipe draw() also does vertex processing on this thread), of which the LOD step
(prepare), its p99, background CPU ms a frame (the renderer's worker threads), GPU ms (timer
queries), triangles, and GPU waits a frame as median/max (calls that made the render thread
wait for the GPU: 0 is right).
"""
import json
import sys
from pathlib import Path

RUNS = ["korea-flyover", "korea-flyover-big", "globe-descent", "globe-lowflight", "stacks-flyover"]


def row(name, report, algo):
    s = algo["summary"]
    width, height = report["size"]
    return (f"| {algo['algo']} | {name} ({report['path']}, {width}x{height}) "
            f"| {s['frame_ms_median']:.2f} | {s['cpu_thread_ms_median']:.3f} "
            f"| {s['cpu_lod_thread_ms_median']:.3f} | {s['cpu_thread_ms_p99']:.3f} "
            f"| {s['background_cpu_ms_median']:.2f} | {s['gpu_ms_median']:.2f} "
            f"| {s['triangles_median']:,.0f} "
            f"| {s.get('gpu_waits_median', float('nan')):.0f}/{s.get('gpu_waits_max', float('nan')):.0f} |")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: gpu_check_table.py OUT_DIR")
    folder = Path(sys.argv[1])
    reports = [(name, folder / f"{name}.json") for name in RUNS]
    present = [(name, json.loads(path.read_text())) for name, path in reports if path.exists()]
    if not present:
        sys.exit(f"gpu_check_table: no bench reports in {folder}")
    machine = present[0][1]["machine"]
    print(f"GL renderer: {machine['gl_renderer']} ({machine['gl_version']}); "
          f"CPU: {machine['cpu']}, {machine['hardware_threads']} hardware threads; "
          f"{present[0][1]['frames']} frames after {present[0][1]['warmup_frames']} warm-up.\n")
    print("| renderer | run | frame ms | render-thread CPU ms | of it LOD | render-thread p99 "
          "| background CPU ms | GPU ms | triangles | GPU waits med/max |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, report in present:
        for algo in report["algorithms"]:
            print(row(name, report, algo))
    missing = [name for name, path in reports if not path.exists()]
    if missing:
        print(f"\nNot run: {', '.join(missing)}.")


if __name__ == "__main__":
    main()
