#!/usr/bin/env bash
# The README's rosrun lines work as written: rosrun finds each program of the package exactly
# once (it ignores programs under <package>/build/, and asks the user to choose when it finds
# two), and the command-line lines run. Needs the devel space's environment (ctest gives it
# through env.sh).
# usage: readme_commands_test.sh README.md
set -euo pipefail
readme=$1
cd "$(dirname "$readme")"
fail=0
mapfile -t programs < <(grep -oE 'rosrun placement_samplers [A-Za-z0-9_.]+' "$readme" | awk '{print $3}' | sort -u)
[ "${#programs[@]}" -ge 4 ] || { echo "expected at least 4 rosrun lines in $readme"; exit 1; }
for p in "${programs[@]}"; do
  # --prefix echo prints the path rosrun resolved instead of running it; stdin closed, so an
  # ambiguous name (rosrun's "choose one" prompt) fails.
  if path=$(rosrun --prefix echo placement_samplers "$p" </dev/null 2>&1) && [ -x "$path" ]; then
    echo "ok: rosrun placement_samplers $p -> $path"
  else
    echo "FAIL: rosrun placement_samplers $p: $path"
    fail=1
  fi
done
# The README's own command lines that need no running node, run as written.
while IFS= read -r line; do
  cmd=${line%%#*}
  echo "running: $cmd"
  if ! out=$(bash -c "$cmd" 2>&1 </dev/null); then
    echo "FAIL: $cmd"
    echo "$out" | tail -n 5
    fail=1
  fi
done < <(grep -E '^rosrun placement_samplers (sample_scenes|sample_client.py --help)' "$readme")
exit $fail
