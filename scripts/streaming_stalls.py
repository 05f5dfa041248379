#!/usr/bin/env python3
"""Frame stalls of `tellus bench --json` reports (docs/ecosystem.md): per report and renderer,
the median frame ms, the frames over twice the median (stalls), the render thread's slowest
LOD step, and the tiles wanted but not resident.

    scripts/streaming_stalls.py LABEL=report.json [LABEL=report.json ...]
"""
import json
import statistics
import sys


def main(arguments):
    if not arguments:
        sys.exit(__doc__)
    print("| source | renderer | frames | frame ms median | stalls (> 2x median) | slowest frame ms | LOD max ms | misses |")
    print("|---|---|---|---|---|---|---|---|")
    for argument in arguments:
        label, _, path = argument.partition("=")
        with open(path) as f:
            report = json.load(f)
        for algorithm in report["algorithms"]:
            frames = algorithm["frames"]
            times = [frame["frame_ms"] for frame in frames]
            median = statistics.median(times)
            stalls = sum(1 for t in times if t > 2 * median)
            lod_max = max(frame["cpu_lod_ms"] for frame in frames)
            misses = sum(frame["cache_misses"] for frame in frames)
            print(f"| {label} | {algorithm['algo']} | {len(frames)} | {median:.1f} | {stalls} | "
                  f"{max(times):.1f} | {lod_max:.2f} | {misses} |")


if __name__ == "__main__":
    main(sys.argv[1:])
