#!/usr/bin/env bash
# Runs the paper's experiments with `biped run` and draws their figures.
#   experiments/run.sh            (what `make experiments` calls after building)
# Outputs: out/experiments/<name>/{summary.json,log.csv}, figures in docs/figures/.
# Any failing run or plot stops the script with a non-zero exit status.
set -euo pipefail
cd "$(dirname "$0")/.."

BIPED=${BIPED:-build/biped}
OUT=${OUT:-out/experiments}
FIGURES=${FIGURES:-docs/figures}
PYTHON=/usr/bin/python3          # the system python with python3-matplotlib (not a pyenv one)
export PYTHONDONTWRITEBYTECODE=1  # no __pycache__ in the source tree
PLOT="$PYTHON experiments/plot.py"

[ -x "$BIPED" ] || { echo "experiments: $BIPED missing (make build)" >&2; exit 1; }
mkdir -p "$OUT" "$FIGURES"
SECONDS=0

run() {  # run NAME SCENARIO [--set ...]
  local name=$1 scenario=$2; shift 2
  echo "experiments: $name  ($BIPED run $scenario $*)"
  if ! "$BIPED" run "$scenario" --out "$OUT/$name" "$@"; then
    echo "experiments: FAILED: $BIPED run $scenario $* (exit status $?)" >&2
    exit 1
  fi
  [ -s "$OUT/$name/summary.json" ] && [ -s "$OUT/$name/log.csv" ] ||
    { echo "experiments: FAILED: $OUT/$name has no summary.json/log.csv" >&2; exit 1; }
}

run fig6-lola-straight experiments/fig6-lola-straight.yaml
run fig7-johnnie-circle experiments/fig7-johnnie-circle.yaml
run disturbance-lola-on experiments/disturbance-lola.yaml --set controller.stabilizer=true
run disturbance-lola-off experiments/disturbance-lola.yaml --set controller.stabilizer=false
run disturbance-lola-off-nopush experiments/disturbance-lola.yaml --set controller.stabilizer=false \
  --set 'disturbances=[]'

$PLOT fig6 "$OUT/fig6-lola-straight" experiments/fig6-lola-straight.yaml "$FIGURES/fig6-lola-straight.png"
$PLOT fig7 "$OUT/fig7-johnnie-circle" experiments/fig7-johnnie-circle.yaml "$FIGURES/fig7-johnnie-circle.png"
$PLOT disturbance "$OUT/disturbance-lola-on" "$OUT/disturbance-lola-off" experiments/disturbance-lola.yaml \
  "$FIGURES/disturbance-lola.png" "$OUT/disturbance-lola-off-nopush"

# Gain sweeps of the tuning guide (docs/tuning.md).
BIPED=$BIPED OUT=$OUT FIGURES=$FIGURES experiments/tuning.sh

# One line per run: the numbers experiments/README.md quotes.
$PYTHON - "$OUT" <<'PY'
import json, os, sys
sys.path.insert(0, "experiments")
from plot import Run
out = sys.argv[1]
for name in ["fig6-lola-straight", "fig7-johnnie-circle", "disturbance-lola-on", "disturbance-lola-off",
             "disturbance-lola-off-nopush"]:
    s = json.load(open(os.path.join(out, name, "summary.json")))
    t = s["upper_body_tilt_deg"]
    fall = f"fell at {s['fall_time_s']:.2f} s ({s['fall_reason']})" if s["fell"] else "no fall"
    if s["fell"]:
        rx, ry = Run(os.path.join(out, name)).rms_before_fall()
        fall += f"; walking until 2 s before the fall: RMS phi_x {rx:.2f} deg, phi_y {ry:.2f} deg"
    print(f"experiments: {name:28s} RMS phi_x {t['rms_x']:.2f} deg, phi_y {t['rms_y']:.2f} deg, "
          f"max {t['max']:.2f} deg, {s['distance_m']:.2f} m, {s['steps']} steps, {fall}")
PY
echo "experiments: done in ${SECONDS} s; runs in $OUT/, figures:"
ls -1 "$FIGURES"/fig6-lola-straight.png "$FIGURES"/fig7-johnnie-circle.png "$FIGURES"/disturbance-lola.png \
  "$FIGURES"/tuning-eq10.png "$FIGURES"/tuning-force.png | sed 's/^/  /'
