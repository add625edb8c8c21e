#!/usr/bin/python3
"""Figures of the paper's experiments from `biped run` outputs (log.csv, summary.json).

Usage (system python, /usr/bin/python3, with python3-matplotlib and python3-yaml):
  plot.py fig6        RUN_DIR SCENARIO.yaml OUT.(png|svg)
  plot.py fig7        RUN_DIR SCENARIO.yaml OUT.(png|svg)
  plot.py disturbance ON_DIR OFF_DIR SCENARIO.yaml OUT.(png|svg) [OFF_NO_PUSH_DIR]
  plot.py tuning eq10|force SCENARIO.yaml OUT.(png|svg) GAIN=VALUE:RUN_DIR...
      one row per gain (controller.stabilization.GAIN), one line per value; eq10: the upper-body
      angle after each push of the scenario; force: desired against measured contact wrench

Everything drawn comes from the run directories and the scenario file; nothing is hard-coded.
Exit status 1 (with a message) when an input is missing or malformed.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402

# Deterministic SVG output (no random ids, no date), so re-running gives the same file.
matplotlib.rcParams["svg.hashsalt"] = "biped"
matplotlib.rcParams["svg.fonttype"] = "none"
matplotlib.rcParams["font.size"] = 9

STATE_COLORS = {"standing": "#dddddd", "starting": "#c6dbef", "walking": "#ffffff",
                "stopping": "#fdd0a2", "safe_stop": "#fcbba1"}
LEFT_SS, RIGHT_SS = "#d9f0d3", "#e7d4e8"  # single support on the left / right foot
PHI_X, PHI_Y = "#1f77b4", "#d62728"
PRE_FALL = 2.0  # [s] the tumble before a detected fall, left out of axis scales and "before the fall" RMS


def die(msg):
    print(f"plot.py: {msg}", file=sys.stderr)
    sys.exit(1)


class Run:
    """One `biped run` output directory."""

    NUMERIC = ["t", "base_x", "base_y", "base_z", "phi_x_deg", "phi_y_deg",
               "left_Fz_des", "right_Fz_des", "left_Fz", "right_Fz", "left_Ty_des", "right_Ty_des",
               "left_Ty", "right_Ty", "left_Tx_des", "right_Tx_des", "left_Tx", "right_Tx",
               "cmd_saturated", "steps_completed"]

    def __init__(self, run_dir):
        self.dir = run_dir
        log, summ = os.path.join(run_dir, "log.csv"), os.path.join(run_dir, "summary.json")
        for f in (log, summ):
            if not os.path.isfile(f):
                die(f"{f}: missing (run `biped run` first)")
        with open(summ) as fh:
            self.summary = json.load(fh)
        cols = {k: [] for k in self.NUMERIC}
        self.state = []
        with open(log, newline="") as fh:
            reader = csv.DictReader(fh)
            missing = [k for k in self.NUMERIC + ["state"] if k not in (reader.fieldnames or [])]
            if missing:
                die(f"{log}: columns missing: {', '.join(missing)}")
            for row in reader:
                for k in self.NUMERIC:
                    cols[k].append(float(row[k]))
                self.state.append(row["state"])
        if not self.state:
            die(f"{log}: no rows")
        for k, v in cols.items():
            setattr(self, k, np.asarray(v))

    def before_fall(self):
        """Mask of the rows up to PRE_FALL s before the fall (all rows when it did not fall)."""
        if self.fell and self.fall_time is not None:
            return self.t < self.fall_time - PRE_FALL
        return np.ones_like(self.t, dtype=bool)

    def rms_before_fall(self):
        """RMS of phi_x, phi_y [deg] while walking, up to PRE_FALL s before a fall."""
        keep = self.before_fall() & np.array([s != "standing" for s in self.state])
        if not keep.any():
            return float("nan"), float("nan")
        return (float(np.sqrt(np.mean(self.phi_x_deg[keep] ** 2))),
                float(np.sqrt(np.mean(self.phi_y_deg[keep] ** 2))))

    @property
    def fell(self):
        return bool(self.summary.get("fell"))

    @property
    def fall_time(self):
        return self.summary.get("fall_time_s")

    def tilt_text(self):
        tilt = self.summary["upper_body_tilt_deg"]
        s = (f"RMS φx {tilt['rms_x']:.2f}°, φy {tilt['rms_y']:.2f}°, max tilt {tilt['max']:.1f}°; "
             f"{self.summary['distance_m']:.1f} m, {self.summary['steps']} steps;\n")
        if self.fell:
            rx, ry = self.rms_before_fall()
            s += (f"FELL at {self.fall_time:.2f} s ({self.summary.get('fall_reason', '')}); \n"
                  f"until {PRE_FALL:.0f} s before it, walking: RMS φx {rx:.2f}°, φy {ry:.2f}°")
        else:
            s += "no fall"
        return s


def spans(t, mask):
    """[(t0, t1)] of the runs where mask is true."""
    out, start = [], None
    for i, m in enumerate(mask):
        if m and start is None:
            start = t[i]
        elif not m and start is not None:
            out.append((start, t[i]))
            start = None
    if start is not None:
        out.append((start, t[-1]))
    return out


def shade_states(ax, run):
    """Background colour per FSM state (white while walking)."""
    t, states = run.t, run.state
    seen = set()
    i = 0
    while i < len(states):
        j = i
        while j + 1 < len(states) and states[j + 1] == states[i]:
            j += 1
        s = states[i]
        color = STATE_COLORS.get(s, "#eeeeee")
        if color != "#ffffff":
            ax.axvspan(t[i], t[min(j + 1, len(t) - 1)], color=color, lw=0,
                       label=f"FSM: {s}" if s not in seen else None, zorder=0)
            seen.add(s)
        i = j + 1


def shade_support(ax, run, t0=None, t1=None):
    """Single support phases from the plan's desired normal forces (swing foot: Fz_des ≈ 0)."""
    sel = np.ones_like(run.t, dtype=bool)
    if t0 is not None:
        sel &= (run.t >= t0) & (run.t <= t1)
    t = run.t[sel]
    left_stance = (run.right_Fz_des[sel] <= 1.0) & (run.left_Fz_des[sel] > 1.0)
    right_stance = (run.left_Fz_des[sel] <= 1.0) & (run.right_Fz_des[sel] > 1.0)
    for k, (a, b) in enumerate(spans(t, left_stance)):
        ax.axvspan(a, b, color=LEFT_SS, lw=0, zorder=0, label="single support, left foot" if k == 0 else None)
    for k, (a, b) in enumerate(spans(t, right_stance)):
        ax.axvspan(a, b, color=RIGHT_SS, lw=0, zorder=0, label="single support, right foot" if k == 0 else None)


def plot_tilt(ax, run, lw=0.9):
    ax.plot(run.t, run.phi_x_deg, color=PHI_X, lw=lw, label="φx (sagittal)")
    ax.plot(run.t, run.phi_y_deg, color=PHI_Y, lw=lw, label="φy (lateral)")
    ax.axhline(0.0, color="k", lw=0.4)
    ax.set_ylabel("angle to gravity [deg]")
    ax.grid(True, lw=0.3, alpha=0.6)


def tilt_limits(ax, run, headroom=1.6):
    """y range from the data up to PRE_FALL s before a fall (the fall itself leaves the axes), with
    room on top for the legend."""
    keep = run.before_fall()
    if not keep.any():
        keep = np.ones_like(run.t, bool)
    lo = float(min(run.phi_x_deg[keep].min(), run.phi_y_deg[keep].min()))
    hi = float(max(run.phi_x_deg[keep].max(), run.phi_y_deg[keep].max()))
    span = max(hi - lo, 0.5)
    ax.set_ylim(lo - 0.1 * span, lo + headroom * span)


def mark_fall(ax, run, label=True):
    if run.fell and run.fall_time is not None:
        ax.axvline(run.fall_time, color="k", lw=1.5, ls="--",
                   label=f"fall {run.fall_time:.2f} s" if label else None)


def commands_of(scenario):
    """Piecewise-constant joystick timeline [(t, vx, vy, omega)] as the scenario reader builds it."""
    out, cur = [], {"vx": 0.0, "vy": 0.0, "omega": 0.0}
    for c in scenario.get("commands") or []:
        for k in cur:
            if k in c:
                cur[k] = float(c[k])
        stop = bool(c.get("stop", False))
        out.append((float(c["t"]), 0.0 if stop else cur["vx"], 0.0 if stop else cur["vy"],
                    0.0 if stop else cur["omega"]))
    return out


def pushes_of(scenario):
    return [(float(d.get("t", 0.0)), float(d.get("duration", 0.1)), [float(f) for f in d["force"]])
            for d in scenario.get("disturbances") or [] if d.get("type") == "push"]


def push_label(force, duration):
    names = ["x", "y", "z"]
    parts = [f"{'+' if f > 0 else '−'}{abs(f):.0f} N {names[i]}" for i, f in enumerate(force) if f != 0.0]
    return f"{', '.join(parts)}, {duration:.2f} s ({math.sqrt(sum(f * f for f in force)) * duration:.0f} N·s)"


def load_scenario(path):
    if not os.path.isfile(path):
        die(f"{path}: missing")
    with open(path) as fh:
        return yaml.safe_load(fh)


def save(fig, out):
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    kw = {"metadata": {"Date": None}} if out.endswith(".svg") else {"metadata": {"Software": None}}
    fig.savefig(out, dpi=110, **kw)
    plt.close(fig)
    print(f"plot.py: wrote {out}")


def steady_window(run, length=4.0):
    """A window of `length` s in the middle of the walking phase (for the close-up)."""
    walking = run.t[np.array([s == "walking" for s in run.state])]
    if walking.size == 0:
        return run.t[0], min(run.t[-1], run.t[0] + length)
    mid = 0.5 * (walking[0] + walking[-1])
    return mid - length / 2, mid + length / 2


def fig6(run_dir, scenario_path, out):
    run, scen = Run(run_dir), load_scenario(scenario_path)
    fig, (a0, a1) = plt.subplots(2, 1, figsize=(9, 6.2), gridspec_kw={"height_ratios": [1, 1]})
    shade_states(a0, run)
    plot_tilt(a0, run)
    mark_fall(a0, run)
    cmds = ", ".join(f"{vx:.1f} m/s from {t:.0f} s" if vx else f"stop at {t:.0f} s"
                     for t, vx, _, _ in commands_of(scen) if t > 0)
    a0.set_title(f"LOLA walking straight ({cmds}), simulated — cf. paper Fig. 6\n{run.tilt_text()}",
                 fontsize=9)
    a0.set_xlim(run.t[0], run.t[-1])
    tilt_limits(a0, run)
    a0.legend(loc="upper right", fontsize=7, ncol=4)
    t0, t1 = steady_window(run)
    sel = (run.t >= t0) & (run.t <= t1)
    shade_support(a1, run, t0, t1)
    a1.plot(run.t[sel], run.phi_x_deg[sel], color=PHI_X, lw=1.2, label="φx (sagittal)")
    a1.plot(run.t[sel], run.phi_y_deg[sel], color=PHI_Y, lw=1.2, label="φy (lateral)")
    a1.axhline(0.0, color="k", lw=0.4)
    a1.grid(True, lw=0.3, alpha=0.6)
    a1.set_xlim(t0, t1)
    a1.set_ylabel("angle to gravity [deg]")
    a1.set_xlabel("t [s]")
    a1.set_title(f"close-up {t0:.1f}–{t1:.1f} s with the walking phases (white: double support)", fontsize=9)
    tilt_limits(a1, run, headroom=1.45)
    a1.legend(loc="upper right", fontsize=7, ncol=4)
    fig.tight_layout()
    save(fig, out)


def fig7(run_dir, scenario_path, out):
    run, scen = Run(run_dir), load_scenario(scenario_path)
    fig = plt.figure(figsize=(10, 7.2))
    gs = fig.add_gridspec(2, 2, height_ratios=[1, 1.15], width_ratios=[1.5, 1])
    a0 = fig.add_subplot(gs[0, :])
    shade_states(a0, run)
    plot_tilt(a0, run, lw=0.7)
    mark_fall(a0, run)
    a0.set_xlim(run.t[0], float(scen["duration"]))
    tilt_limits(a0, run)
    a0.set_title("JOHNNIE walking a circle, joystick changing speed and turn rate, simulated — cf. paper Fig. 7\n"
                 + run.tilt_text(), fontsize=9)
    a0.legend(loc="upper left", fontsize=7, ncol=5)

    a1 = fig.add_subplot(gs[1, 0])
    cmds = commands_of(scen)
    tc = [c[0] for c in cmds] + [float(scen["duration"])]
    vx = [c[1] for c in cmds] + [cmds[-1][1]]
    om = [c[3] for c in cmds] + [cmds[-1][3]]
    a1.step(tc, vx, where="post", color="k", lw=1.2, label="commanded vx [m/s]")
    # Measured pelvis speed over the ground, averaged over 1 s (about two steps).
    dt = np.median(np.diff(run.t))
    n = max(1, int(round(1.0 / dt)))
    if len(run.t) > n:
        v = np.hypot(run.base_x[n:] - run.base_x[:-n], run.base_y[n:] - run.base_y[:-n]) / (run.t[n:] - run.t[:-n])
        tm = 0.5 * (run.t[n:] + run.t[:-n])
        if run.fell:  # not the tumble itself
            v, tm = v[run.t[n:] < run.fall_time], tm[run.t[n:] < run.fall_time]
        a1.plot(tm, v, color="#2ca02c", lw=1.0, label="pelvis speed, 1 s mean [m/s]")
    a1.step(tc, om, where="post", color="#9467bd", lw=1.0, ls="--", label="commanded ω [rad/s]")
    mark_fall(a1, run, label=False)
    a1.set_xlim(run.t[0], float(scen["duration"]))
    a1.set_xlabel("t [s]")
    a1.set_ylabel("speed [m/s], turn rate [rad/s]")
    a1.grid(True, lw=0.3, alpha=0.6)
    a1.legend(loc="upper left", fontsize=7)
    a1.set_title("joystick command and measured speed", fontsize=9)

    a2 = fig.add_subplot(gs[1, 1])
    a2.plot(run.base_x, run.base_y, color="k", lw=1.0, label="pelvis path")
    a2.plot(run.base_x[0], run.base_y[0], "o", color="#2ca02c", label="start")
    if run.fell:
        a2.plot(run.base_x[-1], run.base_y[-1], "x", color="r", ms=9, mew=2, label=f"fall {run.fall_time:.1f} s")
    else:
        a2.plot(run.base_x[-1], run.base_y[-1], "s", color="k", label="end")
    a2.set_aspect("equal", adjustable="datalim")
    a2.set_xlabel("x [m]")
    a2.set_ylabel("y [m]")
    a2.grid(True, lw=0.3, alpha=0.6)
    a2.legend(loc="best", fontsize=7)
    a2.set_title("top view (ground truth)", fontsize=9)
    fig.tight_layout()
    save(fig, out)


def disturbance(on_dir, off_dir, scenario_path, out, ref_dir=None):
    on, off, scen = Run(on_dir), Run(off_dir), load_scenario(scenario_path)
    ref = Run(ref_dir) if ref_dir else None  # stabilizer off, no pushes: when it falls anyway
    pushes = pushes_of(scen)
    duration = float(scen["duration"])
    fig, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex=True, gridspec_kw={"height_ratios": [1.4, 1]})
    # The same tilt scale on both sides, from the stabilized run; the unstabilized one leaves it on
    # its way down (the fall line marks where).
    lim = min(20.0, max(3.0, 1.5 * float(np.max(np.abs(np.concatenate([on.phi_x_deg, on.phi_y_deg]))))))
    zmin = min(on.base_z.min(), off.base_z.min())
    zmax = max(on.base_z.max(), off.base_z.max())
    for col, (run, name) in enumerate([(on, "stabilizer on"), (off, "stabilizer off")]):
        a, b = axes[0, col], axes[1, col]
        shade_support(a, run)
        plot_tilt(a, run, lw=0.8)
        if col == 1 and ref is not None:
            a.plot(ref.t, ref.phi_y_deg, color="#999999", lw=0.8, ls=":", zorder=2,
                   label="φy without pushes" + (f" (fall {ref.fall_time:.2f} s)" if ref.fell else ""))
            b.plot(ref.t, ref.base_z, color="#999999", lw=1.0, ls=":", label="without pushes")
            if ref.fell:
                for ax in (a, b):
                    ax.axvline(ref.fall_time, color="#999999", lw=1.2, ls="--")
        b.plot(run.t, run.base_z, color="k", lw=1.0, label="pelvis height")
        b.legend(loc="lower left", fontsize=6.5)
        b.set_ylabel("pelvis height [m]")
        b.set_xlabel("t [s]")
        b.grid(True, lw=0.3, alpha=0.6)
        b.set_ylim(zmin - 0.02, zmax + 0.02)
        for ax in (a, b):
            for k, (tp, d, f) in enumerate(pushes):
                ax.axvspan(tp, tp + d, color="#ff7f0e", alpha=0.6, lw=0, zorder=1)
                if ax is a:
                    ax.annotate(f"push {k + 1}\n{push_label(f, d)}", xy=(tp, lim * 0.95), fontsize=6.5,
                                ha="left", va="top", color="#a05000",
                                xytext=(3, 0), textcoords="offset points")
            mark_fall(ax, run, label=(ax is a))
        a.set_ylim(-lim, lim)
        a.set_xlim(run.t[0] if col == 0 else on.t[0], duration)
        a.set_title(f"{name}: {run.tilt_text()}", fontsize=8)
        a.legend(loc="lower left", fontsize=6.5, ncol=3)
    fig.suptitle(f"{scen.get('name', '')}: the same walk and pushes (orange) with the stabilizer on and off",
                 fontsize=10)
    fig.tight_layout()
    save(fig, out)


def wrench_error_rms(run, component, t0):
    """RMS over both feet of measured minus desired `component` (Fz, Tx, Ty) from t0 on, while
    walking and before any fall."""
    keep = run.before_fall() & (run.t >= t0) & np.array([s == "walking" for s in run.state])
    if not keep.any():
        return float("nan")
    err = np.concatenate([getattr(run, f"{side}_{component}")[keep] - getattr(run, f"{side}_{component}_des")[keep]
                          for side in ("left", "right")])
    return float(np.sqrt(np.mean(err ** 2)))


def stabilization_defaults(scenario):
    """controller.stabilization of the scenario's robot parameter file (the values a sweep varies)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "config", "robots",
                        f"{scenario.get('robot', '')}.yaml")
    if not os.path.isfile(path):
        die(f"{path}: missing (robot of the scenario)")
    with open(path) as fh:
        return (yaml.safe_load(fh).get("controller") or {}).get("stabilization") or {}


def parse_sweep(specs):
    """[(gain, [(value, Run)])] in command-line order from GAIN=VALUE:RUN_DIR arguments."""
    rows = {}
    for spec in specs:
        if "=" not in spec or ":" not in spec.split("=", 1)[1]:
            die(f"bad sweep entry '{spec}' (GAIN=VALUE:RUN_DIR)")
        gain, rest = spec.split("=", 1)
        value, run_dir = rest.split(":", 1)
        rows.setdefault(gain, []).append((float(value), Run(run_dir)))
    if not rows:
        die("tuning: no GAIN=VALUE:RUN_DIR entries")
    return list(rows.items())


def tuning(kind, scenario_path, out, *specs):
    if kind not in ("eq10", "force"):
        die(f"tuning: unknown kind '{kind}' (eq10, force)")
    scen = load_scenario(scenario_path)
    defaults = stabilization_defaults(scen)
    rows = parse_sweep(specs)
    pushes = pushes_of(scen)
    if kind == "eq10" and len(pushes) < 2:
        die(f"{scenario_path}: tuning eq10 needs two pushes (lateral, then sagittal)")
    fig, axes = plt.subplots(len(rows), 2, figsize=(11, 2.3 * len(rows) + 0.6), squeeze=False)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for r, (gain, runs) in enumerate(rows):
        for k, (value, run) in enumerate(runs):
            color = colors[k % len(colors)]
            label = f"{gain} = {value:g}" + (" (default)" if float(defaults.get(gain, float("nan"))) == value else "")
            if run.fell:
                label += f", FELL at {run.fall_time:.1f} s"
            if kind == "eq10":
                for c, ((tp, d, _), angle) in enumerate(zip(pushes[:2], ("phi_y_deg", "phi_x_deg"))):
                    sel = (run.t >= tp - 0.5) & (run.t <= tp + 4.0)
                    if run.fell:
                        sel &= run.t <= run.fall_time
                    text = label
                    if not run.fell or run.fall_time > tp + 4.0:  # the peak means nothing in a fall
                        text += f"; peak {np.max(np.abs(getattr(run, angle)[sel & (run.t >= tp)])):.1f}°"
                    axes[r][c].plot(run.t[sel], getattr(run, angle)[sel], color=color, lw=1.0, label=text)
            else:
                t0, t1 = steady_window(run, 2.0)
                sel = (run.t >= t0) & (run.t <= t1)
                label += f"; RMS error Fz {wrench_error_rms(run, 'Fz', 3.0):.0f} N, Ty {wrench_error_rms(run, 'Ty', 3.0):.1f} N·m"
                for c, comp in enumerate(("Fz", "Ty")):
                    axes[r][c].plot(run.t[sel], getattr(run, f"left_{comp}")[sel], color=color, lw=1.1,
                                    label=label if c == 0 else None)
                    axes[r][c].plot(run.t[sel], getattr(run, f"left_{comp}_des")[sel], color=color, lw=0.8, ls="--")
        for c in range(2):
            ax = axes[r][c]
            ax.grid(True, lw=0.3, alpha=0.6)
            if kind == "eq10":
                tp, d, f = pushes[c]
                ax.axvspan(tp, tp + d, color="#ff7f0e", alpha=0.6, lw=0)
                ax.set_ylabel(("φy (lateral)" if c == 0 else "φx (sagittal)") + " [deg]")
                ax.set_title(f"push {c + 1}: {push_label(f, d)}", fontsize=8)
                lo, hi = ax.get_ylim()
                ax.set_ylim(max(lo, -8.0), min(hi, 8.0))
                ax.legend(loc="upper right", fontsize=6.5)
            else:
                ax.set_ylabel("left foot " + ("Fz [N]" if c == 0 else "Ty [N·m]"))
                ax.set_title("left foot: measured (solid) and desired λ_d (dashed)", fontsize=8)
                if c == 0:
                    ax.legend(loc="upper right", fontsize=6.5)
        axes[-1][0].set_xlabel("t [s]")
        axes[-1][1].set_xlabel("t [s]")
    what = "contact force modification, eq. (10)" if kind == "eq10" else "force control, eqs. (14), (20)"
    fig.suptitle(f"{scen.get('name', '')}: gains of the {what}, one row per gain "
                 f"(controller.stabilization)", fontsize=10)
    fig.tight_layout()
    save(fig, out)
    for gain, runs in rows:
        for value, run in runs:
            fall = f"fell at {run.fall_time:.2f} s" if run.fell else "no fall"
            rx, ry = run.rms_before_fall()
            print(f"tuning: {gain}={value:g}: {fall}; RMS phi_x {rx:.2f} deg, phi_y {ry:.2f} deg; "
                  f"RMS error Fz {wrench_error_rms(run, 'Fz', 3.0):.1f} N, Tx {wrench_error_rms(run, 'Tx', 3.0):.2f} N m, "
                  f"Ty {wrench_error_rms(run, 'Ty', 3.0):.2f} N m")


def main(argv):
    usage = __doc__.split("\n\n")[1]
    if len(argv) < 2:
        die("missing command\n" + usage)
    cmd, args = argv[1], argv[2:]
    if cmd in ("fig6", "fig7") and len(args) == 3:
        (fig6 if cmd == "fig6" else fig7)(*args)
    elif cmd == "disturbance" and len(args) in (4, 5):
        disturbance(*args)
    elif cmd == "tuning" and len(args) >= 4:
        tuning(*args)
    else:
        die(f"bad arguments: {' '.join(argv[1:])}\n{usage}")


if __name__ == "__main__":
    main(sys.argv)
