#!/usr/bin/env bash
# The closed-loop regression battery: every shipped scenario in full, the unexpected terrain at many
# edge positions (also with sensor noise, with model errors, and for JOHNNIE), the sensor faults at
# several times, the model errors in every variant (the campaign config/campaigns/regression.yaml,
# on every core through the campaign engine), and the speed sweeps of both robots. One line per
# run; the exit status is 1 if any run ends otherwise than expected (a fall where none is expected,
# or no fall where the adaptation is switched off).
#   experiments/regression.sh [--set KEY=VALUE ...]   (after make build; about 1 minute on 2 cores)
# Overrides given apply to every run (an A/B comparison of a parameter change, e.g.
# `--set controller.stabilization.tilt_gain=900`). Outputs: out/regression/campaign/ (campaign.sqlite,
# results.csv, summary.json, report.html with the reproduce command of every run).
set -euo pipefail
cd "$(dirname "$0")/.."

BIPED=${BIPED:-build/biped}
OUT=${OUT:-out/regression}
[ -x "$BIPED" ] || { echo "regression: $BIPED missing (make build)" >&2; exit 1; }
mkdir -p "$OUT"
S=config/scenarios
SECONDS=0

# The overrides, as keys of the campaign's `set:` (applied after each case's own).
campaign_sets=()
sweep_sets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --set) campaign_sets+=(--set "set.$2"); sweep_sets+=(--set "$2"); shift 2 ;;
    --set=*) campaign_sets+=(--set "set.${1#--set=}"); sweep_sets+=(--set "${1#--set=}"); shift ;;
    *) echo "regression: unknown argument $1 (expected --set KEY=VALUE)" >&2; exit 2 ;;
  esac
done

status=0
rm -rf "$OUT/campaign"
"$BIPED" campaign config/campaigns/regression.yaml --out "$OUT/campaign" "${campaign_sets[@]}" >"$OUT/campaign.txt" 2>&1 \
  || { echo "UNEXPECTED  regression campaign failed: $(tail -1 "$OUT/campaign.txt")"; exit 1; }
/usr/bin/python3 - "$OUT/campaign/campaign.sqlite" <<'PY' || status=1
import json, sqlite3, sys
db = sqlite3.connect(sys.argv[1])
bad = 0
for status, error, parameters, fell, fall_time, reason, expected, as_expected, rms_x, rms_y in db.execute(
        "SELECT status, error, parameters, fell, fall_time_s, fall_reason, expected, as_expected, "
        "tilt_rms_x_deg, tilt_rms_y_deg FROM runs ORDER BY run"):
    name = json.loads(parameters)["case"]
    if status != "ok":
        print("UNEXPECTED  %-32s biped run failed: %s" % (name, error)); bad += 1; continue
    outcome = "FELL at %.6f s: %s" % (fall_time, reason) if fell else "no fall"
    mark = "ok" if as_expected else "UNEXPECTED"
    bad += 0 if as_expected else 1
    print("%-10s  %-32s expected %-5s: %s; tilt RMS %.2f/%.2f deg" % (mark, name, expected, outcome, rms_x, rms_y))
sys.exit(1 if bad else 0)
PY

# The speed sweeps: the fastest walk without a fall against the issue's goals. What the robot can
# do: every row of its step table with a positive ZMP margin (min_zmp_margin 0); the joystick's
# default bound keeps 2 cm of margin (LOLA 0.8, JOHNNIE 0.7 m/s; docs/walking.md).
sweep() {  # sweep ROBOT FROM TO GOAL
  local json fastest
  json=$("$BIPED" speed-sweep "$S/$1-walk.yaml" --from "$2" --to "$3" --set controller.limits.min_zmp_margin=0 \
         "${sweep_sets[@]}" | tail -1)
  fastest=$(/usr/bin/python3 -c "import json,sys; print(json.loads(sys.argv[1])['fastest_without_fall_mps'])" "$json")
  if /usr/bin/python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) >= float(sys.argv[2]) - 1e-9 else 1)" "$fastest" "$4"; then
    printf '%-10s  %-32s fastest without a fall %s m/s (goal %s)\n' ok "speed-sweep-$1" "$fastest" "$4"
  else
    printf '%-10s  %-32s fastest without a fall %s m/s (goal %s)\n' UNEXPECTED "speed-sweep-$1" "$fastest" "$4"
    return 1
  fi
}
sweep lola 0.6 1.1 1.0 || status=1     # each sweep runs its speeds on every core
sweep johnnie 0.4 0.9 0.67 || status=1

echo "regression: done in $SECONDS s ($( [ $status = 0 ] && echo 'all as expected' || echo 'SOME UNEXPECTED' ))"
exit $status
