#!/usr/bin/env bash
# sample_scenes --output writes any number of scenes in bounded memory: 2,000,000 Lift scenes
# (138 MB of arrays) with a peak resident set below 64 MB (17 MB measured), measured by /usr/bin/time; numpy
# then reads the file's shapes and its last scene index. Asserts memory, never time.
#   test/npz_memory.sh SAMPLE_SCENES CONFIG [SCENES] [LIMIT_KB]
set -euo pipefail
bin="$1"
config="$2"
scenes="${3:-2000000}"
limit_kb="${4:-64000}"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
status=0
/usr/bin/time -f "%M" -o "$dir/rss" "$bin" --config "$config" --seed 1 --scenes "$scenes" \
  --output "$dir/big.npz" || status=$?
if [ "$status" -gt 1 ]; then
  echo "sample_scenes failed with status $status" >&2
  exit 1
fi
rss_kb=$(tail -n 1 "$dir/rss")
echo "$scenes scenes: peak resident set $rss_kb KB (limit $limit_kb KB), file $(stat -c %s "$dir/big.npz") bytes"
/usr/bin/python3 - "$dir/big.npz" "$scenes" <<'PY'
import sys
import numpy as np
data = np.load(sys.argv[1])
k = int(sys.argv[2])
assert data["position"].shape[0] == k and data["scene"][-1] == k - 1, data["position"].shape
assert data["success"].all()
PY
if [ "$rss_kb" -ge "$limit_kb" ]; then
  echo "peak resident set $rss_kb KB is not below $limit_kb KB" >&2
  exit 1
fi
