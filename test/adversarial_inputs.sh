#!/usr/bin/env bash
# sample_scenes against inputs made to take long or much memory: each ends with a clear
# message, in bounded time and memory. Times are only checked against generous bounds (a
# limit of 1 s must end within 60 s) that prove "does not hang"; peak memory by /usr/bin/time.
#   test/adversarial_inputs.sh SAMPLE_SCENES SOURCE_DIR
set -uo pipefail
bin="$1"
source_dir="$2"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
config="$source_dir/config/default.yaml"
fail=0

# check NAME WANT_STATUS WANT_STDERR_LINE MAX_KB -- COMMAND...: runs COMMAND (stdin from
# $dir/stdin when it exists) with a 60 s timeout, compares its status and its first stderr line
# (WANT_STDERR_LINE is a glob pattern).
check() {
  local name="$1" want_status="$2" want_err="$3" max_kb="$4"
  shift 5
  local status=0
  if [ -e "$dir/stdin" ]; then
    /usr/bin/time -f "%M %e" -o "$dir/time" timeout 60 "$@" > "$dir/out" 2> "$dir/err" \
      < "$dir/stdin" || status=$?
  else
    /usr/bin/time -f "%M %e" -o "$dir/time" timeout 60 "$@" > "$dir/out" 2> "$dir/err" \
      < /dev/null || status=$?
  fi
  rm -f "$dir/stdin"
  local err
  err=$(grep -v '^Command exited' "$dir/err" | head -n 1)
  read -r kb seconds < <(tail -n 1 "$dir/time")
  if [ "$status" != "$want_status" ] || [[ "$err" != $want_err ]] || [ "$kb" -gt "$max_kb" ]; then
    echo "FAIL: $name: status $status (want $want_status), peak $kb KB (at most $max_kb)"
    echo "  stderr: $err"
    echo "  want:   $want_err"
    fail=1
  else
    echo "ok: $name: status $status, ${seconds} s, peak $kb KB"
  fi
}

# A missing field names the line and the field, not the configuration file.
echo '{"scene": 0, "placements": [{"name": "cube"}]}' > "$dir/stdin"
check "missing field" 2 \
  "sample_scenes: --validate <stdin>: line 1: placement 0 ('cube'): missing field \"position\"" \
  65536 -- "$bin" --config "$config" --validate -

# An endless line: refused at 32 MiB.
check "/dev/zero" 2 \
  "sample_scenes: --validate /dev/zero: line 1: longer than 33554432 bytes (the limit of a line)" \
  131072 -- "$bin" --config "$config" --validate /dev/zero

# One line of 40 MB with 500,000 placements: longer than a line may be.
python3 - "$dir/big.jsonl" <<'PY'
import sys
p = '{"name": "cube", "position": [0.1, 0.0, 0.83], "orientation": [0, 0, 0, 1]}'
with open(sys.argv[1], "w") as f:
    f.write('{"scene": 0, "placements": [' + ", ".join([p] * 500000) + "]}\n")
PY
check "40 MB line" 2 \
  "sample_scenes: --validate $dir/big.jsonl: line 1: longer than 33554432 bytes (the limit of a line)" \
  131072 -- "$bin" --config "$config" --validate "$dir/big.jsonl"

# An invalid UTF-8 name: the verdict line is still JSON.
printf '{"placements": [{"name": "b\xff", "position": [0, 0, 0], "orientation": [0, 0, 0, 1]}]}\n' \
  > "$dir/stdin"
check "invalid UTF-8 name" 1 "" 65536 -- "$bin" --config "$config" --validate -
python3 -c 'import json, sys; [json.loads(l) for l in open(sys.argv[1], encoding="utf-8")]' \
  "$dir/out" || { echo "FAIL: the verdict line is not JSON"; fail=1; }

# --output: a FIFO is refused at once (opening it would wait for a reader).
mkfifo "$dir/fifo.npz"
check "FIFO output" 2 \
  "sample_scenes: $dir/fifo.npz: is a FIFO or socket: an .npz file is written at offsets, so it must be a regular file" \
  65536 -- "$bin" --config "$config" --output "$dir/fifo.npz"
check "--validate --output" 2 \
  "sample_scenes: --output writes sampled scenes; --validate prints JSON to stdout instead (drop --output)" \
  65536 -- "$bin" --config "$config" --validate - --output "$dir/x.npz"

# strategy dense in a 1000-vertex polygon with 0.25 mm spheres: about 2.3e9 edge tests, refused
# before any draw.
python3 - "$dir/dense.yaml" "$dir/free_space.yaml" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("objects:\n")
    f.writelines(f"  s{i}: {{shape: sphere, radius: 0.00025}}\n" for i in range(10))
    corners = ", ".join(f"[{0.35 * math.cos(2 * math.pi * k / 1000):.9f}, "
                        f"{0.35 * math.sin(2 * math.pi * k / 1000):.9f}]" for k in range(1000))
    f.write("samplers:\n  - {name: S, strategy: dense, objects: ["
            + ", ".join(f"s{i}" for i in range(10))
            + "], region: {shape: polygon, vertices: [" + corners + "]}}\n")
# free_space: 200 objects of distinct radii, 10,000 keep-out disks (max_attempts 8: one rejection
# attempt, so the cells are built for every object and pruned against every zone).
with open(sys.argv[2], "w") as f:
    f.write("objects:\n")
    f.writelines(f"  o{i}: {{shape: sphere, radius: {0.001 + 0.00001 * i:.6f}}}\n"
                 for i in range(200))
    f.write("samplers:\n  - name: S\n    strategy: free_space\n    max_attempts: 8\n"
            "    x_range: [-1, 1]\n"
            "    y_range: [-1, 1]\n    objects: [" + ", ".join(f"o{i}" for i in range(200))
            + "]\n    keep_out:\n")
    f.writelines(f"      - {{shape: disk, centre: [{-0.99 + 1.98 * (k % 100 + 0.5) / 100:.5f}, "
                 f"{-0.99 + 1.98 * (k // 100 + 0.5) / 100:.5f}], radius: 0.001}}\n"
                 for k in range(10000))
PY
check "dense 1000-gon" 1 \
  "sample_scenes: sampler 'S': strategy dense: about 2269675 lattice sites in the region's bounding box, each tested against 1000 region and keep-out edges, exceed the limit of 250000000 tests a scene (larger objects, a smaller region or fewer vertices)" \
  65536 -- "$bin" --config "$dir/dense.yaml" --seed 1 --threads 1

# The same keep-out zones take more than 30 s a scene to prune: a 1 s limit ends it.
check "free_space 10,000 keep-out zones" 1 \
  "sample_scenes: stopped placing object 'o*' with sampler 'S' after * attempts: the scene ran out of time (its limit is 1 s)" \
  262144 -- \
  "$bin" --config "$dir/free_space.yaml" --seed 1 --threads 1 --max-scene-seconds 1
if ! grep -q 'the scene ran out of time (its limit is 1 s)' "$dir/out"; then
  echo "FAIL: free_space: no time-limit message in: $(cut -c1-300 "$dir/out")"
  fail=1
fi
exit $fail
