#!/usr/bin/python3
"""Seed 004's Figures 26-28: frame time and drawn triangles at each of the 360 one-degree
steps of `tellus bench --path rotate`, one line per RAG setting (one bench JSON each).

usage: plot_rag_figures.py OUTPUT.png TITLE LABEL=REPORT.json [LABEL=REPORT.json ...]
(Debian's python3-matplotlib)
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) < 4 or any("=" not in a for a in argv[3:]):
        sys.exit(__doc__)
    output, title, runs = argv[1], argv[2], [a.split("=", 1) for a in argv[3:]]
    fig, (time_ax, tri_ax) = plt.subplots(1, 2, figsize=(12, 4.2), dpi=110)
    renderer = ""
    for label, path in runs:
        with open(path) as f:
            report = json.load(f)
        renderer = report["machine"]["gl_renderer"]
        frames = report["algorithms"][0]["frames"]
        steps = [frame["index"] for frame in frames]
        time_ax.plot(steps, [frame["frame_ms"] for frame in frames], label=label, linewidth=1.1)
        tri_ax.plot(steps, [frame["triangles"] for frame in frames], label=label, linewidth=1.1)
    time_ax.set_ylabel("frame time (ms)")
    tri_ax.set_ylabel("triangles drawn")
    for ax in (time_ax, tri_ax):
        ax.set_xlabel("rotation step (degrees)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"{title} ({renderer})", fontsize=10)
    fig.tight_layout()
    fig.savefig(output)


if __name__ == "__main__":
    main(sys.argv)
