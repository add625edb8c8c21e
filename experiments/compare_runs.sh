#!/usr/bin/env bash
# Behaviour check across a change: runs every shipped scenario (config/scenarios/, experiments/)
# with two `biped` binaries and compares their log.csv files with the `cycle_us` column removed
# (the only column that is wall-clock time). Prints one line per scenario; exit status 1 when any
# pair differs.
#   experiments/compare_runs.sh REF_BIPED NEW_BIPED [--set KEY=VALUE ...]
# REF_BIPED may be a binary built from another checkout: set REF_DATA_DIR to that checkout so it
# reads its own models and configuration (BIPED_DATA_DIR). Outputs: out/compare/{ref,new}/<name>/.
set -euo pipefail
cd "$(dirname "$0")/.."

[ $# -ge 2 ] || { echo "usage: $0 REF_BIPED NEW_BIPED [--set KEY=VALUE ...]" >&2; exit 2; }
REF=$1 NEW=$2
shift 2
OUT=${OUT:-out/compare}
JOBS=${JOBS:-2}
rm -rf "$OUT"
mkdir -p "$OUT/ref" "$OUT/new"
export REF NEW OUT EXTRA="$*"

# shellcheck disable=SC2317  # called through xargs
one() {
  local file=$1 name
  name=$(basename "$file" .yaml)
  # shellcheck disable=SC2086  # the overrides are separate words
  BIPED_DATA_DIR=${REF_DATA_DIR:-} "$REF" run "$file" $EXTRA --out "$OUT/ref/$name" >/dev/null 2>&1 || {
    echo "ERROR      $name: reference run failed"; return 1; }
  # shellcheck disable=SC2086
  "$NEW" run "$file" $EXTRA --out "$OUT/new/$name" >/dev/null 2>&1 || { echo "ERROR      $name: new run failed"; return 1; }
  local strip='NR==1{for(i=1;i<=NF;i++) if($i=="cycle_us") c=i} {if(c){$c=""} print}'
  if cmp -s <(awk -F, -v OFS=, "$strip" "$OUT/ref/$name/log.csv") <(awk -F, -v OFS=, "$strip" "$OUT/new/$name/log.csv"); then
    echo "identical  $name ($(wc -l <"$OUT/new/$name/log.csv") rows)"
  else
    echo "DIFFERENT  $name"; return 1
  fi
}
export -f one

status=0
ls config/scenarios/*.yaml experiments/*.yaml | xargs -P "$JOBS" -I{} bash -c 'one "$@"' _ {} || status=1
[ $status -eq 0 ] && echo "compare: every log.csv identical apart from cycle_us" || echo "compare: differences (see above)"
exit $status
