#!/usr/bin/env bash
# The closed-loop regression battery: every shipped scenario in full, the unexpected terrain at many
# edge positions (also with sensor noise, with model errors, and for JOHNNIE), the sensor faults at
# several times, the model errors in every variant, and the speed sweeps of both robots. One line
# per run; the exit status is 1 if any run ends otherwise than expected (a fall where none is
# expected, or no fall where the adaptation is switched off).
#   experiments/regression.sh [--set KEY=VALUE ...]   (after make build; about 1 minute on 2 cores)
# Overrides given apply to every run (an A/B comparison of a parameter change, e.g.
# `--set controller.stabilization.tilt_gain=900`). Outputs: out/regression/<name>/{summary.json,
# log.csv}. Runs two at a time.
set -euo pipefail
cd "$(dirname "$0")/.."

BIPED=${BIPED:-build/biped}
OUT=${OUT:-out/regression}
JOBS=${JOBS:-2}
[ -x "$BIPED" ] || { echo "regression: $BIPED missing (make build)" >&2; exit 1; }
mkdir -p "$OUT"
S=config/scenarios
SECONDS=0
EXTRA="$*"

# name | expected (walks / falls) | scenario and overrides
runs() {
  for f in lola-straight lola-walk lola-sensor-noise lola-model-error lola-model-error-mass lola-model-error-com \
           lola-ft-frozen lola-ft-nan johnnie-walk johnnie-circle; do
    echo "$f|walks|$S/$f.yaml"
  done
  echo "lola-model-error-mass-lighter|walks|$S/lola-model-error-mass.yaml --set model_error.upper_body_mass_scale=0.9"
  echo "lola-model-error-com-back|walks|$S/lola-model-error-com.yaml --set model_error.upper_body_com_offset=[-0.02,0,0]"
  echo "lola-model-error-com-sideways|walks|$S/lola-model-error-com.yaml --set model_error.upper_body_com_offset=[0,0.02,0]"
  echo "lola-model-error-lighter|walks|$S/lola-model-error.yaml --set model_error.upper_body_mass_scale=0.9"
  for t in 4.8 5.0 5.3 6.0 6.5 7.0; do echo "lola-ft-nan-at-$t|walks|$S/lola-ft-nan.yaml --set sensors.faults.0.t=$t"; done
  for x in 1.0 1.25 1.3 1.8 1.85 1.9 1.95 2.0 2.05 2.1 2.15 2.2 2.25 2.3 2.35 2.4; do
    echo "step-up-at-$x|walks|$S/lola-terrain-step-up.yaml --set terrain.0.x=$x"
  done
  for x in 1.0 1.25 1.3 1.8 1.85 1.9 1.95 2.0 2.05 2.1 2.15 2.2 2.25 2.3 2.35 2.4 2.45 2.5 2.55 2.6; do
    echo "step-down-at-$x|walks|$S/lola-terrain-step-down.yaml --set terrain.0.x=$x"
  done
  for x in 1.0 2.0; do echo "slope-at-$x|walks|$S/lola-terrain-slope.yaml --set terrain.0.x=$x"; done
  for f in step-up step-down slope; do
    echo "$f-adaptation-off|falls|$S/lola-terrain-$f.yaml --set controller.terrain_adaptation.enabled=false"
    echo "$f-with-sensor-noise|walks|$S/lola-terrain-$f.yaml --set sensors.noise=true --set sensors.delay_cycles=1"
    echo "$f-with-model-error|walks|$S/lola-terrain-$f.yaml --set model_error.upper_body_mass_scale=1.1 --set model_error.upper_body_com_offset=[0.02,0,0]"
    echo "johnnie-$f|walks|$S/lola-terrain-$f.yaml --set robot=johnnie"
  done
}

# shellcheck disable=SC2317  # called through xargs
one() {  # one "name|expected|args": prints the result line, returns 1 if unexpected
  IFS='|' read -r name expected args <<<"$1"
  # shellcheck disable=SC2086  # the overrides are separate words
  if ! "$BIPED" run $args $EXTRA --out "$OUT/$name" >"$OUT/$name.txt" 2>&1; then
    echo "UNEXPECTED  $name: biped run failed: $(tail -1 "$OUT/$name.txt")"; return 1
  fi
  local outcome; outcome=$(head -1 "$OUT/$name.txt" | sed 's/.*real time), //')
  local got=walks; [[ $outcome == FELL* ]] && got=falls
  local tilt; tilt=$(/usr/bin/python3 -c "import json,sys; t=json.load(open(sys.argv[1]))['upper_body_tilt_deg']; print('tilt RMS %.2f/%.2f deg' % (t['rms_x'], t['rms_y']))" "$OUT/$name/summary.json")
  local mark=ok; [ "$got" = "$expected" ] || mark=UNEXPECTED
  printf '%-10s  %-32s expected %-5s: %s; %s\n' "$mark" "$name" "$expected" "$outcome" "$tilt"
  [ "$mark" = ok ]
}
export -f one
export BIPED OUT EXTRA

status=0
runs | xargs -P "$JOBS" -I{} bash -c 'one "$@"' _ {} || status=1

# The speed sweeps: the fastest walk without a fall against the issue's goals.
sweep() {  # sweep ROBOT FROM TO GOAL
  local json fastest
  # shellcheck disable=SC2086
  json=$("$BIPED" speed-sweep "$S/$1-walk.yaml" --from "$2" --to "$3" $EXTRA | tail -1)
  fastest=$(/usr/bin/python3 -c "import json,sys; print(json.loads(sys.argv[1])['fastest_without_fall_mps'])" "$json")
  if /usr/bin/python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) >= float(sys.argv[2]) - 1e-9 else 1)" "$fastest" "$4"; then
    printf '%-10s  %-32s fastest without a fall %s m/s (goal %s)\n' ok "speed-sweep-$1" "$fastest" "$4"
  else
    printf '%-10s  %-32s fastest without a fall %s m/s (goal %s)\n' UNEXPECTED "speed-sweep-$1" "$fastest" "$4"
    return 1
  fi
}
sweep lola 0.6 1.1 1.0 &
sweep johnnie 0.4 0.9 0.67 &
for job in $(jobs -p); do wait "$job" || status=1; done

echo "regression: done in $SECONDS s ($( [ $status = 0 ] && echo 'all as expected' || echo 'SOME UNEXPECTED' ))"
exit $status
