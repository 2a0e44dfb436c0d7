"""Convergence plots of `erpt compare` (or erpt.compare): error versus render time.

    python3 -m erpt.plot compare-out/compare.json -o compare.png

Two log-log panels, MSE and relMSE against seconds, one curve per integrator (the error after
every pass of its time-budgeted render), with a dashed line of slope -1 (error proportional to
1 / time: constant efficiency) for reference.
"""

import argparse
import json
import math
import sys


def _rows(report):
    if isinstance(report, dict):
        return report.get("results", [])
    return list(report)


def plot_compare(report, path, title=None):
    """Draws `report` (compare.json's contents, or erpt.compare's list) to the image `path`."""
    import matplotlib

    matplotlib.use("Agg")  # files only: no display needed
    import matplotlib.pyplot as plt

    rows = _rows(report)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), constrained_layout=True)
    for ax, key, label in ((axes[0], "mse", "MSE"), (axes[1], "rel_mse", "relMSE")):
        ends = []
        for row in rows:
            curve = [p for p in row.get("curve", []) if p["seconds"] > 0 and p[key] > 0]
            if not curve:
                continue
            ax.loglog([p["seconds"] for p in curve], [p[key] for p in curve], marker=".", label=row["integrator"])
            ends.append((curve[-1]["seconds"], curve[-1][key]))
        if ends:
            # Slope -1 through the best end point: constant efficiency.
            t, e = min(ends, key=lambda te: te[0] * te[1])
            lo = min(p["seconds"] for row in rows for p in row.get("curve", []) if p["seconds"] > 0)
            ax.loglog([lo, t], [e * t / lo, e], "k--", linewidth=0.8, label="slope -1")
        ax.set_xlabel("seconds")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize="small")
    if title is None and isinstance(report, dict):
        title = "{} {}x{}, {:g} s each".format(report.get("scene", ""), report.get("width", ""),
                                              report.get("height", ""), report.get("budget_seconds", 0))
    if title:
        fig.suptitle(title)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m erpt.plot", description=__doc__.splitlines()[0])
    parser.add_argument("report", help="compare.json written by `erpt compare`")
    parser.add_argument("-o", "--output", required=True, help="image to write (.png, .pdf, .svg)")
    args = parser.parse_args(argv)
    try:
        with open(args.report) as f:
            report = json.load(f)
    except (OSError, ValueError) as e:
        print(f"{args.report}: error: {e}", file=sys.stderr)
        return 1
    plot_compare(report, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
