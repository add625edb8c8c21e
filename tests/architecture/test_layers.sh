#!/usr/bin/env bash
# The layering rules of docs/architecture.md, checked on the sources: every #include of a project
# header points to the same layer or one the layer may depend on; MuJoCo appears only in model/
# and sim/ (and in io/ and studies/, which drive the simulator); control/, planning/ and model/ do
# no file I/O and print nothing. Prints every violation; exit status 1 if there is any.
set -uo pipefail
src=${1:-$(dirname "$0")/../../src}
cd "$src" || exit 2

declare -A allowed=(
  [math]="math"
  [interface]="interface math"
  [model]="model math"
  [planning]="planning model math"
  [control]="control planning interface model math"
  [sim]="sim interface model math"
  [io]="io sim control planning interface model math"
  [studies]="studies io sim control planning interface model math"
  [apps]="apps studies io sim control planning interface model math"
)

status=0
for layer in "${!allowed[@]}"; do
  [ -d "$layer" ] || { echo "missing layer folder src/$layer"; status=1; continue; }
  while IFS=: read -r file line include; do
    target=${include#*\"}
    target=${target%%/*}
    if [[ " ${allowed[$layer]} " != *" $target "* ]]; then
      echo "src/$file:$line: $layer/ may not include $target/ ($include)"
      status=1
    fi
  done < <(grep -n '^#include "' "$layer"/* /dev/null | sed 's/^\([^:]*\):\([0-9]*\):/\1:\2:/')
done

for layer in control planning interface math; do
  if grep -nE 'mj[A-Z_][A-Za-z_]*|mujoco/mujoco.h|->mj\(\)|\.mj\(\)' "$layer"/* ; then
    echo "^ $layer/ uses MuJoCo directly (use the functions of model/)"
    status=1
  fi
done
for layer in control planning model interface math; do
  if grep -nE '#include <(fstream|iostream|cstdio)>|std::(cout|cerr|ifstream|ofstream)|printf\(' "$layer"/*; then
    echo "^ $layer/ does file I/O or prints (that belongs in io/)"
    status=1
  fi
done
for layer in math interface model planning control sim io; do
  if grep -n '#include <mpi.h>' "$layer"/*; then
    echo "^ $layer/ uses MPI (only studies/ and apps/ may)"
    status=1
  fi
done
[ $status -eq 0 ] && echo "layers: every include and MuJoCo use where docs/architecture.md allows it"
exit $status
