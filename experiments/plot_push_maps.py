"""Push-recovery maps side by side (polar: radius = largest survived impulse, angle = push direction
in the heading frame, 0° forward up, 90° left), with the capture-point bound without a step, and one
line of numbers per map.
    python3 experiments/plot_push_maps.py OUT.png MAP_DIR...
"""
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(d):
    with open(f"{d}/push_map.json") as f:
        return json.load(f)


def main():
    out, dirs = sys.argv[1], sys.argv[2:]
    maps = [load(d) for d in dirs]
    cols = 2
    rows = math.ceil(len(maps) / cols)
    fig, axes = plt.subplots(rows, cols, subplot_kw={"projection": "polar"}, figsize=(5.2 * cols, 4.6 * rows))
    axes = axes.ravel() if hasattr(axes, "ravel") else [axes]
    top = max([c["max_impulse_Ns"] or 0 for m in maps for c in m["cells"]] +
              [b["max_impulse_Ns"] for m in maps for b in m["capture_point_bound_Ns"]])
    for ax, d, m in zip(axes, dirs, maps):
        phases = sorted({c["phase"] if c["phase"] is not None else -1 for c in m["cells"]})
        cmap = plt.get_cmap("viridis")
        for i, p in enumerate(phases):
            cells = sorted((c["direction_deg"], c["max_impulse_Ns"]) for c in m["cells"]
                           if (c["phase"] if c["phase"] is not None else -1) == p and c["max_impulse_Ns"] is not None)
            if not cells:
                continue
            th = [math.radians(a) for a, _ in cells] + [math.radians(cells[0][0])]
            r = [v for _, v in cells] + [cells[0][1]]
            label = "standing" if p < 0 else f"phase {p:.3g}"
            ax.plot(th, r, color=cmap(i / max(1, len(phases) - 1)), lw=1.4, label=label)
        bound = sorted((b["direction_deg"], b["max_impulse_Ns"]) for b in m["capture_point_bound_Ns"])
        th = [math.radians(a) for a, _ in bound] + [math.radians(bound[0][0])]
        ax.plot(th, [v for _, v in bound] + [bound[0][1]], "k--", lw=1.2, label="bound without a step")
        ax.set_theta_zero_location("N")
        ax.set_ylim(0, top * 1.05)
        speed = d.rstrip("/").split("/")[-1]
        ax.set_title(f"{speed}: stabilizer {'on' if m['stabilizer'] else 'off'}", fontsize=10)
        ax.tick_params(labelsize=7)
        vals = [c["max_impulse_Ns"] for c in m["cells"] if c["max_impulse_Ns"] is not None]
        falls = sum(1 for c in m["cells"] if c.get("falls_without_push"))
        worst = min(m["cells"], key=lambda c: c["max_impulse_Ns"] if c["max_impulse_Ns"] is not None else 1e9)
        print(f"{speed:14s} stabilizer {'on ' if m['stabilizer'] else 'off'}: cells {len(m['cells'])}, "
              f"largest survived impulse min {min(vals):.1f} / median {sorted(vals)[len(vals)//2]:.1f} / max {max(vals):.1f} N·s"
              f" (weakest: {worst['direction_deg']}° at phase {worst['phase']}), falls without a push in {falls} cells")
    for ax in axes[len(maps):]:
        ax.set_visible(False)
    # The legend of the map with the most curves (a walking map names every phase).
    richest = max(axes[:len(maps)], key=lambda a: len(a.get_lines()))
    richest.legend(loc="upper left", bbox_to_anchor=(1.05, 1.1), fontsize=6)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
