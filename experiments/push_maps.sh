#!/usr/bin/env bash
# The first push-recovery maps (docs/campaigns.md "Push-recovery maps"): LOLA standing (0.0 m/s),
# walking at 0.3 and 0.6 m/s, stabilizer on and off; each map DIRECTIONS x PHASES cells, every cell
# the push test's search to 1 N·s, on every core through the campaign engine (resumable: run again
# after an interruption and it continues). Then docs/figures/push-maps-lola.png and one line per map.
#   experiments/push_maps.sh [DIRECTIONS [PHASES]]      (defaults 16 8; after make build)
set -euo pipefail
cd "$(dirname "$0")/.."
BIPED=${BIPED:-build/biped}
OUT=${OUT:-out/push-maps}
DIRECTIONS=${1:-16}
PHASES=${2:-8}
[ -x "$BIPED" ] || { echo "push_maps: $BIPED missing (make build)" >&2; exit 1; }
SECONDS=0
maps=()
for speed in 0.0 0.3 0.6; do
  for stabilizer in true false; do
    name="lola-$speed-$([ $stabilizer = true ] && echo on || echo off)"
    # lola-push.yaml: walk from 1 s at the speed, stop at 7 s, stand until 12 s; pushes in the first
    # single support after 4 s (standing: at 4 s).
    "$BIPED" push-map config/scenarios/lola-push.yaml --out "$OUT/$name" --directions "$DIRECTIONS" --phases "$PHASES" \
      --set commands.1.vx=$speed --set controller.stabilizer=$stabilizer
    maps+=("$OUT/$name")
  done
done
/usr/bin/python3 experiments/plot_push_maps.py docs/figures/push-maps-lola.png "${maps[@]}"
echo "push_maps: done in $SECONDS s"
