#!/usr/bin/env bash
# The joystick slammed between its extremes, one random timeline per seed: every 0.3-1.5 s a new
# setting of vx from {-0.3, 0.6, 1.0, 1.0} m/s (beyond a robot's limit: saturated), vy from
# {-0.15, 0, 0.15} m/s and ω from {-0.5, 0, 0.5} rad/s, until 16 s, then a stop; run with
# `biped run`. Prints one line per run and the count without a fall. The timelines are the same on
# every machine (Python's random, seeded); each run's sensor seed is seed % 97 + 1.
# With PERIOD set, one timeline instead: full reversals on every axis, (0.8, 0.15, 0.5) and
# (-0.3, -0.15, -0.5) alternating every PERIOD s from 1 s to 15 s, then a stop (sensor seed FIRST_SEED).
#   [ROBOT=lola] [PERIOD=0.5] experiments/joystick_slams.sh [FIRST_SEED [COUNT]] [-- --set KEY=VALUE ...]
# docs/walking.md ("Command shaping") quotes seeds 2000-2009 (the training set) and 3000-3019.
set -euo pipefail
cd "$(dirname "$0")/.."
BIPED=${BIPED:-build/biped}
ROBOT=${ROBOT:-lola}
FIRST=${1:-2000}
COUNT=${2:-10}
shift $(( $# > 2 ? 2 : $# ))
[ "${1:-}" = "--" ] && shift
OUT=${OUT:-out/joystick-slams}
mkdir -p "$OUT"
PERIOD=${PERIOD:-}
[ -n "$PERIOD" ] && COUNT=1
python3 - "$FIRST" "$COUNT" "$OUT" "$ROBOT" "$PERIOD" <<'PY'
import random, sys
first, count, out, robot, period = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
if period:
    t, k, lines = 1.0, 0, ["  - {t: 0.0, vx: 0.0}"]
    while t < 15:
        lines.append("  - {t: %.2f, vx: %s, vy: %s, omega: %s}" % ((t,) + ((0.8, 0.15, 0.5) if k % 2 == 0 else (-0.3, -0.15, -0.5))))
        t += float(period)
        k += 1
    lines.append("  - {t: 15.0, stop: true}")
    with open("%s/slam-%s-%d.yaml" % (out, robot, first), "w") as f:
        f.write("name: reversals-%s\nrobot: %s\nduration: 19\nseed: %d\ncommands:\n%s\n" % (period, robot, first, "\n".join(lines)))
    sys.exit(0)
for seed in range(first, first + count):
    r = random.Random(seed)
    t, lines = 1.0, ["  - {t: 0.0, vx: 0.0}"]
    while t < 16:
        vx = r.choice([-0.3, 1.0, 1.0, 0.6])
        vy = r.choice([-0.15, 0.15, 0.0])
        om = r.choice([-0.5, 0.5, 0.0])
        lines.append("  - {t: %.2f, vx: %s, vy: %s, omega: %s}" % (t, vx, vy, om))
        t += r.uniform(0.3, 1.5)
    lines.append("  - {t: %.2f, stop: true}" % t)
    with open("%s/slam-%s-%d.yaml" % (out, robot, seed), "w") as f:
        f.write("name: slam-%d\nrobot: %s\nduration: %.1f\nseed: %d\ncommands:\n%s\n"
                % (seed, robot, t + 5, seed % 97 + 1, "\n".join(lines)))
PY
walked=0
for ((s = FIRST; s < FIRST + COUNT; ++s)); do
  line=$("$BIPED" run "$OUT/slam-$ROBOT-$s.yaml" --out "$OUT/slam-$ROBOT-$s" "$@" 2>&1 | grep -v '^warning' | head -1)
  echo "$line"
  case "$line" in *"no fall"*) walked=$((walked + 1)) ;; esac
done
echo "joystick slams ($ROBOT): $walked of $COUNT without a fall"
