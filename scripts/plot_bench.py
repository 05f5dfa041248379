#!/usr/bin/python3
"""Charts for `tellus bench --plots DIR`: frame time, triangles and CPU (the render thread's
LOD work and the background threads') over the path, the screen-space error histogram and the popping per frame (with --quality) and a contact sheet of
sampled frames; with --quality and several renderers, the comparison of them all
(comparison.png: triangles against SSE p99, marker area by frame time, beside a table sorted by
frame time with cracks and popping; the same table as comparison.md).

usage: plot_bench.py REPORT.json OUTPUT_FOLDER   (Debian's python3-matplotlib)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def title(report, what):
    return f"{what} — path {report['path']}, {report['size'][0]}x{report['size'][1]}, {report['machine']['gl_renderer']}"


def colour_of(report, name):
    """One colour per renderer on every chart: its place in the report (tab10, tab20 beyond)."""
    names = [a["algo"] for a in report["algorithms"]]
    i = names.index(name)
    return plt.cm.tab10(i) if len(names) <= 10 else plt.cm.tab20(i % 20)


def legend_outside(ax, **kwargs):
    """The legend right of the plot, never over the data."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, **kwargs)


def save(fig, folder, filename):
    fig.savefig(os.path.join(folder, filename), bbox_inches="tight")
    plt.close(fig)


def line_chart(report, key, ylabel, what, filename, folder):
    fig, ax = plt.subplots(figsize=(9, 4.5), dpi=110)
    for algo in report["algorithms"]:
        frames = algo["frames"]
        ax.plot([f["index"] for f in frames], [f[key] for f in frames], label=algo["algo"], linewidth=1.4,
                color=colour_of(report, algo["algo"]))
    ax.set_xlabel("frame along the path")
    ax.set_ylabel(ylabel)
    ax.set_title(title(report, what), fontsize=9)
    ax.grid(alpha=0.3)
    ax.set_ylim(bottom=0)
    legend_outside(ax, fontsize=8)
    fig.tight_layout()
    save(fig, folder, filename)


def cpu_chart(report, folder):
    """CPU per frame: the render thread's prepare (LOD, culling, uploads; its CPU clock, and
    wall time, which also counts preemption) and the background threads' CPU (tile loads,
    RINGO's reorganisation and copies), the seed 002 Figure 5 view of a border crossing."""
    fig, ax = plt.subplots(figsize=(9, 4.5), dpi=110)
    for algo in report["algorithms"]:
        frames = algo["frames"]
        index = [f["index"] for f in frames]
        colour = colour_of(report, algo["algo"])
        ax.plot(index, [f.get("cpu_lod_thread_ms", f["cpu_lod_ms"]) for f in frames], linewidth=1.4,
                color=colour, label=algo["algo"])
        ax.plot(index, [f["cpu_lod_ms"] for f in frames], linewidth=0.6, alpha=0.45, color=colour)
        ax.plot(index, [f.get("background_cpu_ms", 0.0) for f in frames], linewidth=1.2,
                linestyle="--", color=colour)
    ax.set_xlabel("frame along the path")
    ax.set_ylabel("CPU ms per frame")
    ax.set_yscale("symlog", linthresh=0.1)
    ax.set_title(title(report, "CPU per frame"), fontsize=9)
    ax.grid(alpha=0.3)
    # Two legends outside the plot: the colour is the renderer, the line what was timed.
    renderers = ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize=8,
                          title="renderer", title_fontsize=8)
    ax.add_artist(renderers)
    styles = [Line2D([], [], color="grey", linewidth=1.4, label="render thread, prepare (CPU clock)"),
              Line2D([], [], color="grey", linewidth=0.6, alpha=0.45, label="render thread, prepare (wall)"),
              Line2D([], [], color="grey", linewidth=1.2, linestyle="--", label="background threads (CPU)")]
    ax.legend(handles=styles, loc="lower left", bbox_to_anchor=(1.01, 0.0), borderaxespad=0.0, fontsize=8,
              title="line", title_fontsize=8)
    fig.tight_layout()
    save(fig, folder, "cpu.png")


def error_histogram(report, folder):
    fig, ax = plt.subplots(figsize=(9, 4.5), dpi=110)
    largest = max((a["summary"].get("sse_px_max", 0.0) for a in report["algorithms"]), default=0.0)
    # 0.01 px bins when every error is small, else 0.1 px bins, up to 20 px at most.
    bin_px = 0.01 if largest < 2.0 else 0.1
    for algo in report["algorithms"]:
        h = algo.get("error_histogram")
        if not h or not h["bins"]:
            continue
        total = sum(count for _, count in h["bins"])
        coarse = {}
        for index, count in h["bins"]:
            start = int(index * h["bin_px"] / bin_px + 1e-9) * bin_px
            coarse[start] = coarse.get(start, 0) + count
        xs = sorted(x for x in coarse if x < 20.0)
        ax.bar(xs, [coarse[x] / total for x in xs], width=bin_px, align="edge", alpha=0.6,
               color=colour_of(report, algo["algo"]),
               label=f"{algo['algo']} (mean {algo['summary']['sse_px_mean']:.3f} px, "
                     f"p95 {algo['summary']['sse_px_p95']:.2f} px, "
                     f"p99 {algo['summary']['sse_px_p99']:.2f} px)")
    ax.set_xlabel(f"screen-space error (pixels, {bin_px} px bins)")
    ax.set_ylabel("fraction of terrain pixels")
    ax.set_yscale("log")
    ax.set_title(title(report, "Screen-space error over all frames"), fontsize=9)
    ax.grid(alpha=0.3)
    legend_outside(ax, fontsize=8)
    fig.tight_layout()
    save(fig, folder, "error_histogram.png")


def contact_sheet(report, folder):
    kept = report.get("kept_frames", [])
    algos = [a["algo"] for a in report["algorithms"]]
    if not kept:
        return
    columns = max(sum(1 for k in kept if k["algo"] == a and "cracks_file" not in k) or 1 for a in algos)
    fig, axes = plt.subplots(len(algos), columns, figsize=(3.2 * columns, 2.1 * len(algos)), dpi=110, squeeze=False)
    for row, algo in enumerate(algos):
        frames = [k for k in kept if k["algo"] == algo][:columns]
        for col in range(columns):
            ax = axes[row][col]
            ax.axis("off")
            if col < len(frames):
                ax.imshow(mpimg.imread(os.path.join(folder, frames[col]["file"])))
                ax.set_title(f"{algo}, frame {frames[col]['index']}", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "contact_sheet.png"))
    plt.close(fig)


def comparison_rows(report):
    """One row per renderer, sorted by median frame time (fastest first)."""
    rows = []
    for algo in report["algorithms"]:
        s = algo["summary"]
        rows.append({"algo": algo["algo"], "frame_ms": s["frame_ms_median"],
                     "cpu_ms": s["cpu_ms_median"], "gpu_ms": s["gpu_ms_median"],
                     "triangles": s["triangles_median"], "sse_p95": s["sse_px_p95"],
                     "sse_p99": s["sse_px_p99"], "cracks": s["crack_pixels_total"],
                     "pop_p99": s["pop_px_p99"]})
    return sorted(rows, key=lambda r: r["frame_ms"])


COLUMNS = [("algo", "renderer", "{}"), ("frame_ms", "frame ms", "{:.1f}"), ("cpu_ms", "CPU ms", "{:.2f}"),
           ("gpu_ms", "GPU ms", "{:.1f}"), ("triangles", "triangles", "{:,.0f}"),
           ("sse_p95", "SSE p95 px", "{:.2f}"), ("sse_p99", "SSE p99 px", "{:.2f}"),
           ("cracks", "crack px", "{}"), ("pop_p99", "popping p99 px", "{:.2f}")]


def comparison_table_markdown(report, folder):
    rows = comparison_rows(report)
    lines = ["| " + " | ".join(label for _, label, _ in COLUMNS) + " |",
             "|" + "|".join(["---"] + ["---:"] * (len(COLUMNS) - 1)) + "|"]
    for row in rows:
        lines.append("| " + " | ".join(fmt.format(row[key]) for key, _, fmt in COLUMNS) + " |")
    with open(os.path.join(folder, "comparison.md"), "w") as f:
        f.write(f"{report['path']} path, {report['frames']} frames, {report['size'][0]}x{report['size'][1]}, "
                f"{report['machine']['gl_renderer']}; medians over the frames, sorted by frame time\n\n")
        f.write("\n".join(lines) + "\n")


def comparison_chart(report, folder):
    """Every renderer on one chart: triangles per frame against SSE p99 (log-log), the marker's
    area growing linearly with the median frame time (60 + 2400 * t / slowest points^2);
    beside it the table sorted by frame time."""
    rows = comparison_rows(report)
    fig = plt.figure(figsize=(11, 6.2 + 0.22 * len(rows)), dpi=110)
    table_height = (1.2 + 0.22 * len(rows)) / (6.2 + 0.22 * len(rows))
    ax = fig.add_axes([0.09, table_height + 0.14, 0.86, 0.80 - table_height])
    slowest = max(r["frame_ms"] for r in rows) or 1.0
    for row in rows:
        colour = colour_of(report, row["algo"])
        area = 60.0 + 2400.0 * row["frame_ms"] / slowest
        ax.scatter([max(row["triangles"], 1)], [max(row["sse_p99"], 1e-3)], s=area, color=colour,
                   alpha=0.55, edgecolors="black", linewidths=0.6)
        ax.annotate(f"{row['algo']}\n{row['frame_ms']:.1f} ms", (max(row["triangles"], 1), max(row["sse_p99"], 1e-3)),
                    textcoords="offset points", xytext=(8, 6), fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("triangles per frame (median)")
    ax.set_ylabel("screen-space error p99 (px)")
    ax.set_title(title(report, "Triangles vs error, marker area = frame time"), fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.margins(0.25)
    table_ax = fig.add_axes([0.02, 0.01, 0.96, table_height])
    table_ax.axis("off")
    cells = [[fmt.format(row[key]) for key, _, fmt in COLUMNS] for row in rows]
    table = table_ax.table(cellText=cells, colLabels=[label for _, label, _ in COLUMNS], loc="upper center",
                           cellLoc="right", colLoc="right")
    table.auto_set_font_size(False)
    table.set_fontsize(9)
    table.scale(1.0, 1.35)
    for (r, c), cell in table.get_celld().items():
        if r > 0 and c == 0:
            cell.set_text_props(ha="left")
            cell.get_text().set_color(colour_of(report, rows[r - 1]["algo"]))
            cell.get_text().set_fontweight("bold")
    table_ax.set_title("sorted by frame time (medians over the frames; crack pixels summed)", fontsize=8)
    fig.savefig(os.path.join(folder, "comparison.png"))
    plt.close(fig)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        report = json.load(f)
    folder = sys.argv[2]
    line_chart(report, "frame_ms", "frame time (ms)", "Frame time", "frame_time.png", folder)
    line_chart(report, "triangles", "triangles per frame", "Triangles", "triangles.png", folder)
    cpu_chart(report, folder)
    if report.get("quality"):
        error_histogram(report, folder)
        line_chart(report, "pop_px_p99", "popping, p99 over the frame's pixels (px)",
                   "Popping (LOD changes alone)", "popping.png", folder)
        if len(report["algorithms"]) > 1:
            comparison_chart(report, folder)
            comparison_table_markdown(report, folder)
    contact_sheet(report, folder)


if __name__ == "__main__":
    main()
