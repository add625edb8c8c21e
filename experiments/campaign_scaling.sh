#!/usr/bin/env bash
# Scaling of the campaign engine on this machine, in one go: the same campaign (lola-user.yaml,
# RUNS runs of DURATION simulated seconds) with 1 and 2 threads, and under mpirun with 1 and 2
# ranks; the speed-ups, the engine's own overhead per run, and a paper estimate for a cluster.
#   experiments/campaign_scaling.sh [RUNS [DURATION]]     (defaults 32 10; after make build)
set -euo pipefail
cd "$(dirname "$0")/.."
BIPED=${BIPED:-build/biped}
OUT=${OUT:-out/campaign-scaling}
RUNS=${1:-32}
DURATION=${2:-10}
[ -x "$BIPED" ] || { echo "campaign_scaling: $BIPED missing (make build)" >&2; exit 1; }
command -v mpirun >/dev/null || { echo "campaign_scaling: mpirun missing (scripts/install-deps.sh)" >&2; exit 1; }
rm -rf "$OUT"
mkdir -p "$OUT"
spec=config/campaigns/lola-user.yaml
sets=(--set runs="$RUNS" --set set.duration="$DURATION" --set generators.joystick.end="$(/usr/bin/python3 -c "print(max(1.0, $DURATION - 3))")")
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$BIPED" campaign "$spec" --out "$OUT/threads-1" --jobs 1 "${sets[@]}" 2>/dev/null
"$BIPED" campaign "$spec" --out "$OUT/threads-2" --jobs 2 "${sets[@]}" 2>/dev/null
mpirun --allow-run-as-root --oversubscribe -n 1 "$BIPED" campaign "$spec" --out "$OUT/ranks-1" "${sets[@]}" 2>/dev/null
mpirun --allow-run-as-root --oversubscribe -n 2 "$BIPED" campaign "$spec" --out "$OUT/ranks-2" "${sets[@]}" 2>/dev/null
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$OUT" "$RUNS" <<'PY'
import json, sqlite3, sys
out, runs = sys.argv[1], int(sys.argv[2])
s = {k: json.load(open(f"{out}/{k}/summary.json")) for k in ["threads-1", "threads-2", "ranks-1", "ranks-2"]}
def rows(k):
    db = sqlite3.connect(f"{out}/{k}/campaign.sqlite")
    return db.execute("SELECT run, status, parameters, command, result FROM runs ORDER BY run").fetchall()
same = all(rows(k) == rows("threads-1") for k in s)
one = s["threads-1"]
mean_run = one["run_time_s"] / runs
overhead = (one["wall_time_s"] - one["run_time_s"]) / runs
print(f"campaign: {runs} runs of lola-user.yaml; identical rows across the four: {same}")
for k, v in s.items():
    print(f"  {k:10s} wall {v['wall_time_s']:7.2f} s, run time {v['run_time_s']:7.2f} s, "
          f"{3600 * runs / v['wall_time_s']:7.0f} runs/h, storing {1e3 * v['storing_s_per_run']:.2f} ms/run")
print(f"speed-up 2 threads / 1: {one['wall_time_s'] / s['threads-2']['wall_time_s']:.2f}x; "
      f"2 ranks / 1: {s['ranks-1']['wall_time_s'] / s['ranks-2']['wall_time_s']:.2f}x")
print(f"mean run {mean_run:.3f} s; engine overhead per run (1 thread: wall - sum of runs) {1e3 * overhead:.2f} ms "
      f"= {100 * overhead / mean_run:.2f} % of a run; coordinator storing {1e3 * one['storing_s_per_run']:.2f} ms/run")
eff = s["ranks-1"]["wall_time_s"] / s["ranks-2"]["wall_time_s"] / 2
store = max(v["storing_s_per_run"] for v in s.values())
cores = 1000
rate = cores * eff * 3600 / mean_run
coordinator_limit = 3600 / store if store > 0 else float("inf")
print(f"paper estimate, {cores} cores at this machine's per-core speed and the 2-rank efficiency {eff:.2f}: "
      f"{rate:,.0f} runs/h of this campaign; one coordinator stores at most {coordinator_limit:,.0f} results/h")
PY
