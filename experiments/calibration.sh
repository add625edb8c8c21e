#!/usr/bin/env bash
# The sensor calibration (controller.calibration, docs/stabilizer.md) on against off:
#  1. LOLA's walk (config/scenarios/lola-walk.yaml, 0.6 m/s, 20 s, the realistic sensor errors) with
#     the IMU mounted 2° off in eight directions (roll = 2° cos a, pitch = 2° sin a) on seeds 1–3;
#  2. the walk with the robot file's drawn sensor errors only, seeds 1–4: the error of the tilt the
#     controller uses against the true one (log.csv: est_phi_* against phi_*, from 1 s on).
# One line per run; outputs in out/calibration/<name>/.
#   experiments/calibration.sh [--set KEY=VALUE ...]   (after make build; about 5 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
BIPED=${BIPED:-build/biped}
OUT=${OUT:-out/calibration}
JOBS=${JOBS:-2}
[ -x "$BIPED" ] || { echo "calibration: $BIPED missing (make build)" >&2; exit 1; }
mkdir -p "$OUT"
EXTRA="$*"

runs() {
  for on in true false; do
    for seed in 1 2 3; do
      for a in 0 45 90 135 180 225 270 315; do
        local r p
        r=$(/usr/bin/python3 -c "import math; print('%.3f' % (2*math.cos(math.radians($a))))")
        p=$(/usr/bin/python3 -c "import math; print('%.3f' % (2*math.sin(math.radians($a))))")
        echo "misaligned-2deg-at-$a-seed-$seed-calibration-$on|--set seed=$seed --set sensors.imu.misalignment_deg=[$r,$p,0] --set controller.calibration.enabled=$on"
      done
    done
    for seed in 1 2 3 4; do
      echo "drawn-errors-seed-$seed-calibration-$on|--set seed=$seed --set controller.calibration.enabled=$on"
    done
  done
}

# shellcheck disable=SC2317  # called through xargs
one() {
  IFS='|' read -r name args <<<"$1"
  # shellcheck disable=SC2086  # the overrides are separate words
  "$BIPED" run config/scenarios/lola-walk.yaml $args $EXTRA --out "$OUT/$name" >"$OUT/$name.txt" 2>&1 || {
    echo "$name: biped run failed: $(tail -1 "$OUT/$name.txt")"; return 0; }
  /usr/bin/python3 - "$OUT/$name" "$name" "$(head -1 "$OUT/$name.txt" | sed 's/.*real time), //')" <<'EOF'
import csv, math, sys
rows = [r for r in csv.DictReader(open(sys.argv[1] + "/log.csv")) if float(r["t"]) >= 1.0 and r["state"] != "fallen"]
def rms(a, b): return math.sqrt(sum((float(r[a]) - float(r[b])) ** 2 for r in rows) / len(rows))
print("%-48s %-40s tilt error RMS (used − true) %.2f/%.2f deg, IMU − true %.2f/%.2f deg" % (
    sys.argv[2], sys.argv[3][:40], rms("est_phi_x_deg", "phi_x_deg"), rms("est_phi_y_deg", "phi_y_deg"),
    rms("imu_phi_x_deg", "phi_x_deg"), rms("imu_phi_y_deg", "phi_y_deg")))
EOF
}
export -f one
export BIPED OUT EXTRA
runs | xargs -P "$JOBS" -I{} bash -c 'one "$@"' _ {} | sort
