#!/usr/bin/env bash
# Random joystick timelines for LOLA (vx -0.3..0.8 m/s, vy ±0.15, ω ±0.5, a change every 0.8-3 s,
# then a stop), one scenario per seed, run with `biped run`; prints one line per run and the count
# of runs without a fall. The timelines are the same on every machine (Python's random, seeded).
#   experiments/joystick_timelines.sh [FIRST_SEED [COUNT]] [-- --set KEY=VALUE ...]
# docs/walking.md ("Command shaping") quotes seeds 1000-1011.
set -euo pipefail
cd "$(dirname "$0")/.."
BIPED=${BIPED:-build/biped}
FIRST=${1:-1000}
COUNT=${2:-12}
shift $(( $# > 2 ? 2 : $# ))
[ "${1:-}" = "--" ] && shift
OUT=${OUT:-out/joystick}
mkdir -p "$OUT"
python3 - "$FIRST" "$COUNT" "$OUT" <<'PY'
import random, sys
first, count, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
for seed in range(first, first + count):
    r = random.Random(seed)
    t, lines = 1.0, ["  - {t: 0.0, vx: 0.0}"]
    while t < 14:
        vx = round(r.uniform(-0.3, 0.8), 2)
        vy = round(r.choice([0, 0, r.uniform(-0.15, 0.15)]), 3)
        om = round(r.choice([0, r.uniform(-0.5, 0.5)]), 2)
        lines.append("  - {t: %.2f, vx: %s, vy: %s, omega: %s}" % (t, vx, vy, om))
        t += r.uniform(0.8, 3.0)
    lines.append("  - {t: %.2f, stop: true}" % t)
    with open("%s/joystick-%d.yaml" % (out, seed), "w") as f:
        f.write("name: joystick-%d\nrobot: lola\nduration: %.1f\nseed: %d\ncommands:\n%s\n"
                % (seed, t + 4, seed - first + 1, "\n".join(lines)))
PY
walked=0
for ((s = FIRST; s < FIRST + COUNT; ++s)); do
  line=$("$BIPED" run "$OUT/joystick-$s.yaml" --out "$OUT/joystick-$s" "$@" 2>&1 | head -1)
  echo "$line"
  case "$line" in *"no fall"*) walked=$((walked + 1)) ;; esac
done
echo "joystick timelines: $walked of $COUNT without a fall"
