#!/usr/bin/env bash
# Gain sweeps for the tuning guide (docs/tuning.md): each gain of controller.stabilization varied
# around its default with everything else fixed, one `biped run` per value, one figure per group.
#   experiments/tuning.sh        (run.sh calls it; the same BIPED, OUT, FIGURES variables)
# Outputs: out/experiments/tuning/<gain>=<value>/, docs/figures/tuning-eq10.png, tuning-force.png.
set -euo pipefail
cd "$(dirname "$0")/.."

BIPED=${BIPED:-build/biped}
OUT=${OUT:-out/experiments}/tuning
FIGURES=${FIGURES:-docs/figures}
PYTHON=/usr/bin/python3
export PYTHONDONTWRITEBYTECODE=1

# Contact force modification, eq. (10): the disturbance walk (a lateral and a backward push).
EQ10_SCENARIO=experiments/disturbance-lola.yaml
EQ10_SWEEP="tilt_gain=0,300,600,1200 tilt_rate_gain=0,60,180 com_gain=0,300,900 com_rate_gain=0,30,90
            cop_margin=0,0.02,0.04"
# Force control, eqs. (14) and (20): the Fig. 6 walk at 0.6 m/s, its first 10 s.
FORCE_SCENARIO=experiments/fig6-lola-straight.yaml
FORCE_SWEEP="force_gain=5,20,60 feedforward_gain=0,0.5,1 force_integral_gain=0,100,300
             contact_stiffness=2e5,4e5,8e5"

sweep() {  # sweep SCENARIO "GAIN=V1,V2 ..." [--set ...]; prints the GAIN=VALUE:DIR list for plot.py
  local scenario=$1 spec=$2; shift 2
  local entry gain value
  for entry in $spec; do
    gain=${entry%%=*}
    IFS=, read -ra values <<< "${entry#*=}"
    for value in "${values[@]}"; do
      local dir="$OUT/$gain=$value"
      if ! "$BIPED" run "$scenario" --out "$dir" --set "controller.stabilization.$gain=$value" "$@" > /dev/null; then
        echo "tuning: FAILED: $BIPED run $scenario --set controller.stabilization.$gain=$value $*" >&2
        exit 1
      fi
      echo "$gain=$value:$dir"
    done
  done
}

mkdir -p "$OUT" "$FIGURES"
echo "tuning: eq. (10) gains on $EQ10_SCENARIO"
eq10_runs=$(sweep "$EQ10_SCENARIO" "$EQ10_SWEEP")
$PYTHON experiments/plot.py tuning eq10 "$EQ10_SCENARIO" "$FIGURES/tuning-eq10.png" $eq10_runs
echo "tuning: force-control gains on $FORCE_SCENARIO (first 10 s)"
force_runs=$(sweep "$FORCE_SCENARIO" "$FORCE_SWEEP" --set duration=10)
$PYTHON experiments/plot.py tuning force "$FORCE_SCENARIO" "$FIGURES/tuning-force.png" $force_runs
