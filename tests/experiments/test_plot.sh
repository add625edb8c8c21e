#!/usr/bin/env bash
# The experiment plots work on a short run: a 2.5 s walk (pushed twice) through `biped run`, then every
# plot command of experiments/plot.py on it; each figure must exist and be more than a blank canvas.
# /usr/bin/python3 needs matplotlib and PyYAML (scripts/install-deps.sh, run by every make target).
# Usage: test_plot.sh BIPED_BINARY SOURCE_DIR
set -euo pipefail
biped=$1 src=$2
export PYTHONDONTWRITEBYTECODE=1
if ! /usr/bin/python3 -c 'import matplotlib, yaml' 2>/dev/null; then
  echo "FAIL: /usr/bin/python3 lacks matplotlib/yaml (run scripts/install-deps.sh)"; exit 1
fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/short.yaml" <<'YAML'
name: plot-test
robot: lola
duration: 2.5
seed: 1
commands:
  - {t: 0.0, vx: 0.0}
  - {t: 0.5, vx: 0.3}
disturbances:
  - {type: push, t: 1.5, body: upper_body, force: [0, 20, 0], duration: 0.1}
  - {type: push, t: 2.0, body: upper_body, force: [-20, 0, 0], duration: 0.1}
YAML
"$biped" run "$tmp/short.yaml" --out "$tmp/on" > /dev/null
"$biped" run "$tmp/short.yaml" --out "$tmp/off" --set controller.stabilizer=false > /dev/null
plot="/usr/bin/python3 $src/experiments/plot.py"
$plot fig6 "$tmp/on" "$tmp/short.yaml" "$tmp/fig6.png"
$plot fig7 "$tmp/on" "$tmp/short.yaml" "$tmp/fig7.svg"
$plot disturbance "$tmp/on" "$tmp/off" "$tmp/short.yaml" "$tmp/dist.png" "$tmp/off"
$plot tuning eq10 "$tmp/short.yaml" "$tmp/tuning-eq10.png" tilt_gain=600:"$tmp/on" tilt_gain=0:"$tmp/off" \
  com_gain=300:"$tmp/on" > /dev/null
$plot tuning force "$tmp/short.yaml" "$tmp/tuning-force.svg" force_gain=20:"$tmp/on" force_gain=5:"$tmp/off" > /dev/null
grep -q 'force_gain = 20 (default)' "$tmp/tuning-force.svg" || { echo "FAIL: tuning-force.svg lacks the default's label"; exit 1; }
for f in fig6.png fig7.svg dist.png tuning-eq10.png tuning-force.svg; do
  size=$(stat -c %s "$tmp/$f")
  [ "$size" -gt 20000 ] || { echo "FAIL: $f only $size bytes"; exit 1; }
done
head -c 8 "$tmp/fig6.png" | od -An -tx1 | grep -q '89 50 4e 47' || { echo "FAIL: fig6.png is not a PNG"; exit 1; }
grep -q 'φx' "$tmp/fig7.svg" || { echo "FAIL: fig7.svg has no φx legend"; exit 1; }
# A bad argument list is an error, not a silent success.
if $plot fig6 "$tmp/on" 2>/dev/null; then echo "FAIL: plot.py accepted missing arguments"; exit 1; fi
if $plot fig6 "$tmp/missing" "$tmp/short.yaml" "$tmp/x.png" 2>/dev/null; then echo "FAIL: plot.py accepted a missing run"; exit 1; fi
if $plot tuning force "$tmp/short.yaml" "$tmp/x.png" force_gain=20 2>/dev/null; then echo "FAIL: plot.py accepted a sweep entry without a run"; exit 1; fi
echo "OK"
