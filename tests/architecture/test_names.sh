#!/usr/bin/env bash
# Test names are stable: letters, digits and _ . / - only, so no parameter's printed value (or an
# object's bytes, which change from build to build) ends up in a name ctest and scripts select by.
# Usage: test_names.sh BUILD_DIR
set -euo pipefail
names=$(ctest --test-dir "$1" -N | sed -n 's/^ *Test *#[0-9]*: //p')
[ -n "$names" ] || { echo "no tests listed in $1"; exit 1; }
bad=$(grep -v -E '^[A-Za-z0-9_./-]+$' <<< "$names" || true)
if [ -n "$bad" ]; then
  echo "test names with other characters (give the INSTANTIATE_TEST_SUITE_P a name generator):"
  echo "$bad"
  exit 1
fi
echo "$(wc -l <<< "$names") test names, all stable"
