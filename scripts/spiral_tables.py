#!/usr/bin/env python3
"""Seed 001's Tables 1 and 3 for the spiral globe, measured with `tellus bench`.

Table 1: GPU and CPU ms per frame and CPU idle for three image sizes and three spirals, with the
full shader (the Blue Marble textures) and the seed's 'white' one. Table 3: GPU ms at 1000 x 1000
with the shader's features removed one by one (each row removes the rows above too).

  scripts/spiral_tables.py TELLUS STORE --textures BLUE_MARBLE_DIR [--geoid GTX] [--frames N]
                           [--path orbit] [--out DIR]

Every run writes its JSON report into DIR; the tables are printed as Markdown. Frames end with
glFinish (bench --finish): frame ms is the whole frame's wall time, GPU work included (llvmpipe's
timer queries miss its fragment shading). CPU ms is the render thread's prepare() and submit;
CPU idle = 1 - CPU ms / frame ms (on llvmpipe vertex shading runs inside the submit, so little
is idle here: on a GPU the submit is a few calls).
"""
import argparse
import json
import pathlib
import subprocess
import sys

# (label, spin step degrees, spin to double): about the seed's 2,146, 4,294 and 17,058 triangles
# from orbit, with triangles about as long as wide (spin to double ~ 0.11 n).
SPIRALS = [("small", 9, 4.5), ("medium", 6, 6.5), ("large", 3, 13.0)]
SIZES = [600, 800, 1000]
# Table 3's cumulative removals, in the seed's order.
FEATURES = ["clouds", "night", "tangent", "bump", "specular", "diffuse"]


def run_spiral_bench(args, name, path, warmup, extra):
    """One `tellus bench --algo spiral --finish` run, its JSON in args.out/NAME.json; the summary.
    Shared with spiral_table2.py."""
    out = pathlib.Path(args.out) / f"{name}.json"
    command = [args.tellus, "bench", args.store, "--algo", "spiral", "--path", str(path),
               "--frames", str(args.frames), "--warmup", str(warmup), "--finish",
               "--json", str(out)] + extra
    if args.geoid:
        command += ["--geoid", args.geoid]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"{' '.join(command)} failed:\n{result.stdout}\n{result.stderr}")
    return json.loads(out.read_text())["algorithms"][0]["summary"]


def bench(args, name, extra):
    return run_spiral_bench(args, name, args.path, 3, extra + ["--spiral-textures", args.textures])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("tellus")
    parser.add_argument("store")
    parser.add_argument("--textures", required=True, help="the Blue Marble folder")
    parser.add_argument("--geoid")
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--path", default="orbit")
    parser.add_argument("--out", default="spiral-tables")
    args = parser.parse_args()
    pathlib.Path(args.out).mkdir(parents=True, exist_ok=True)

    print("Table 1 (medians):\n")
    print("| size | spiral (step, to double) | triangles | frame ms | CPU ms | CPU idle "
          "| frame ms white | CPU ms white | CPU idle white |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for size in reversed(SIZES):
        for label, step, double in reversed(SPIRALS):
            cells = []
            triangles = 0
            for white in (False, True):
                extra = ["--size", f"{size}x{size}", "--spiral-spin-step", str(step),
                         "--spiral-spin-to-double", str(double)]
                if white:
                    extra.append("--spiral-white")
                s = bench(args, f"t1-{size}-{label}{'-white' if white else ''}", extra)
                triangles = triangles or s["triangles_median"]
                cpu, frame = s["cpu_ms_median"], s["frame_ms_median"]
                idle = 100.0 * max(0.0, 1.0 - cpu / frame) if frame > 0 else 0.0
                cells += [f"{frame:.2f}", f"{cpu:.2f}", f"{idle:.0f} %"]
            print(f"| {size}^2 | {label} ({step}, {double}) | {triangles:.0f} | " +
                  " | ".join(cells) + " |")

    print("\nTable 3 (1000 x 1000, medians; each row removes the rows above too):\n")
    print("| feature removed | frame ms | CPU ms |")
    print("|---|---:|---:|")
    removed = []
    for feature in [None] + FEATURES + ["white"]:
        extra = ["--size", "1000x1000"]
        if feature == "white":
            extra.append("--spiral-white")
        elif feature:
            removed.append(feature)
        if removed and feature != "white":
            extra += ["--spiral-without", ",".join(removed)]
        s = bench(args, f"t3-{feature or 'none'}", extra)
        print(f"| {feature or 'none (complete)'} | {s['frame_ms_median']:.2f} | "
              f"{s['cpu_ms_median']:.2f} |")


if __name__ == "__main__":
    main()
