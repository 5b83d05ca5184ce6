#!/usr/bin/env bash
# scripts/slurm without Slurm: sample_array.sbatch run by hand as tasks 0-3 (SLURM_ARRAY_TASK_ID)
# and merge.py's file equal array for array to one process's run; the script's usage errors; and
# merge.py on every kind of bad task (failed, stopped by SIGTERM, lost, truncated, another seed,
# other scenes, never started, data that fails its CRC, tasks of two runs): each named with its reason, nothing written,
# one sbatch command for exactly those tasks.
# usage: merge_test.sh SAMPLE_SCENES SOURCE_DIR
set -euo pipefail
export SAMPLE_SCENES=$1
root=$2
script=$root/scripts/slurm/sample_array.sbatch
merge=$root/scripts/slurm/merge.py
config=$root/config/default.yaml
python=/usr/bin/python3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
unset SLURM_ARRAY_TASK_ID SLURM_ARRAY_TASK_MAX SLURM_CPUS_PER_TASK SLURM_JOB_PARTITION \
  SLURM_ARRAY_JOB_ID SLURM_JOB_ID
host=$(hostname)

fail() {
  echo "FAIL: $*"
  exit 1
}
# expect STATUS LINE CMD...: CMD exits with STATUS and prints LINE (a whole line) on stderr.
expect() {
  local want=$1 line=$2 status=0 err
  shift 2
  err=$("$@" 2>&1 >/dev/null) || status=$?
  [ "$status" -eq "$want" ] || fail "$*: status $status, expected $want; stderr: $err"
  grep -qxF -- "$line" <<<"$err" || fail "$*: expected the line '$line' in: $err"
}
task() {  # task T OUT_DIR [FLAGS...]: task T of 4 by hand
  local t=$1 out=$2
  shift 2
  SLURM_ARRAY_TASK_ID=$t SLURM_ARRAY_TASK_MAX=3 "$script" "$config" 7 50 "$out" "$@" >/dev/null
}
record_time() {
  $python -c 'import json,sys; print(json.load(open(sys.argv[1]))["time"])' "$1"
}

# Usage errors (status 2, nothing started).
expect 2 "sample_array.sbatch: SLURM_ARRAY_TASK_ID: expected the task's index (0, 1, ...), got '' (submit with sbatch --array, or set it)" \
  "$script" "$config" 7 50 "$dir/x"
expect 2 "sample_array.sbatch: SEED: expected a positive integer (0 = random would differ between tasks), got '0'" \
  env SLURM_ARRAY_TASK_ID=0 "$script" "$config" 0 50 "$dir/x"
expect 2 "sample_array.sbatch: SEED: expected a positive integer (0 = random would differ between tasks), got '00'" \
  env SLURM_ARRAY_TASK_ID=0 "$script" "$config" 00 50 "$dir/x"
expect 2 "sample_array.sbatch: --describe: prints JSON lines, not a piece of a data set" \
  env SLURM_ARRAY_TASK_ID=0 "$script" "$config" 7 50 "$dir/x" --describe
expect 2 "sample_array.sbatch: --scenes: this script sets --config, --seed, --scenes, --first-scene, --output and --threads itself" \
  env SLURM_ARRAY_TASK_ID=0 "$script" "$config" 7 50 "$dir/x" --scenes 3
expect 2 "sample_array.sbatch: CONFIG: no readable file '$dir/none.yaml'" \
  env SLURM_ARRAY_TASK_ID=0 "$script" "$dir/none.yaml" 7 50 "$dir/x"
[ ! -e "$dir/x" ] || fail "a usage error created OUT_DIR"

# Four tasks by hand, merged = one process.
for t in 0 1 2 3; do task "$t" "$dir/good"; done
"$SAMPLE_SCENES" --config "$config" --seed 7 --scenes 200 --output "$dir/one.npz"
"$merge" "$dir/good" "$dir/merged.npz"
$python "$root/test/slurm/npz_equal.py" "$dir/merged.npz" "$dir/one.npz" ||
  fail "merged by-hand tasks differ from one process"
! compgen -G "$dir/good/*.partial.npz" >/dev/null || fail "a .partial.npz was left"
# The same pieces give the same bytes (fixed time stamps, as sample_scenes' own files).
"$merge" "$dir/good" "$dir/merged_again.npz" >/dev/null
cmp -s "$dir/merged.npz" "$dir/merged_again.npz" || fail "two merges of the same pieces differ"
rerun="  sbatch --array=%s $script $config 7 50 $dir/bad"

# Bad tasks, each named with its reason.
cp -r "$dir/good" "$dir/bad"
printf '#!/bin/sh\necho "sample_scenes: the disk is on fire" >&2\nexit 2\n' >"$dir/broken"
chmod +x "$dir/broken"
status=0
SAMPLE_SCENES=$dir/broken task 1 "$dir/bad" 2>/dev/null || status=$?
[ "$status" -eq 1 ] || fail "a failing sample_scenes: the task's status $status, expected 1"
printf '#!/bin/sh\nexec sleep 30\n' >"$dir/slow"
chmod +x "$dir/slow"
SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_MAX=3 SAMPLE_SCENES=$dir/slow \
  "$script" "$config" 7 50 "$dir/bad" >/dev/null 2>&1 &
pid=$!
for _ in $(seq 100); do
  grep -q '"state": "running"' "$dir/bad/task_000000.json" 2>/dev/null && pgrep -P "$pid" >/dev/null && break
  sleep 0.1
done
kill -TERM "$pid"
status=0
wait "$pid" || status=$?
[ "$status" -eq 143 ] || fail "SIGTERM: the task's status $status, expected 143"
[ ! -e "$dir/bad/task_000000.npz" ] && [ ! -e "$dir/bad/task_000000.partial.npz" ] ||
  fail "a stopped task left a piece"
rm "$dir/bad/task_000002.npz"
truncate -s 1000 "$dir/bad/task_000003.npz"
expect 1 "  task 0: stopped by a signal (scancel or the time limit) on $host at $(record_time "$dir/bad/task_000000.json")" \
  "$merge" "$dir/bad" "$dir/m.npz"
expect 1 "  task 1: failed on $host at $(record_time "$dir/bad/task_000001.json"): sample_scenes exited with status 2: sample_scenes: the disk is on fire" \
  "$merge" "$dir/bad" "$dir/m.npz"
expect 1 "  task 2: done on $host at $(record_time "$dir/bad/task_000002.json"), but task_000002.npz is not in OUT_DIR" \
  "$merge" "$dir/bad" "$dir/m.npz"
expect 1 "  task 3: task_000003.npz: not a complete .npz (File is not a zip file)" \
  "$merge" "$dir/bad" "$dir/m.npz"
expect 1 "merge.py: 4 of 4 tasks are missing or not usable; nothing written:" \
  "$merge" "$dir/bad" "$dir/m.npz"
# shellcheck disable=SC2059
expect 1 "$(printf "$rerun" 0-3)" "$merge" "$dir/bad" "$dir/m.npz"
[ ! -e "$dir/m.npz" ] || fail "merge.py wrote a file from bad pieces"

# Pieces of another seed or other scenes under a task's name; a task that never started.
rm -rf "$dir/bad" && cp -r "$dir/good" "$dir/bad"
"$SAMPLE_SCENES" --config "$config" --seed 8 --first-scene 50 --scenes 50 --output "$dir/bad/task_000001.npz"
"$SAMPLE_SCENES" --config "$config" --seed 7 --first-scene 101 --scenes 50 --output "$dir/bad/task_000002.npz"
rm "$dir/bad/task_000003".*
expect 1 "  task 1: task_000001.npz: seed 8, expected 7" "$merge" "$dir/bad" "$dir/m.npz"
expect 1 "  task 2: task_000002.npz: scene 101 at row 0, expected scenes 100 .. 149" \
  "$merge" "$dir/bad" "$dir/m.npz"
expect 1 "  task 3: missing: nothing of it in OUT_DIR (it never started)" "$merge" "$dir/bad" "$dir/m.npz"
# shellcheck disable=SC2059
expect 1 "$(printf "$rerun" 1-3)" "$merge" "$dir/bad" "$dir/m.npz"
# --tasks: the array is larger than its tasks said.
# shellcheck disable=SC2059
expect 1 "$(printf "${rerun/bad/good}" 4-5)" "$merge" "$dir/good" "$dir/m.npz" --tasks 6

# A piece whose data went bad after it was written: found by its CRC while copying.
rm -rf "$dir/bad" && cp -r "$dir/good" "$dir/bad"
$python - "$dir/bad/task_000001.npz" <<'PY'
import struct, sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as z:
    info = z.getinfo("position.npy")
with open(sys.argv[1], "r+b") as f:
    f.seek(info.header_offset + 26)
    name_len, extra_len = struct.unpack("<HH", f.read(4))
    f.seek(info.header_offset + 30 + name_len + extra_len + info.file_size - 8)  # the last double
    byte = f.read(1)
    f.seek(-1, 1)
    f.write(bytes([byte[0] ^ 1]))
PY
expect 1 "  task 1: task_000001.npz: Bad CRC-32 for file 'position.npy'" "$merge" "$dir/bad" "$dir/m.npz"
# shellcheck disable=SC2059
expect 1 "$(printf "$rerun" 1)" "$merge" "$dir/bad" "$dir/m.npz"
[ ! -e "$dir/m.npz" ] && ! compgen -G "$dir/.merge.*" >/dev/null || fail "merge.py left a file after a CRC error"

# Two runs in one folder: which is right is the user's call (status 2).
rm -rf "$dir/bad" && cp -r "$dir/good" "$dir/bad"
SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_MAX=3 "$script" "$config" 9 50 "$dir/bad" >/dev/null
expect 2 "merge.py: $dir/bad holds tasks of 2 different runs (configuration, its SHA-256, seed, scenes per task, flags):" \
  "$merge" "$dir/bad" "$dir/m.npz"
[ ! -e "$dir/m.npz" ] || fail "merge.py wrote a file from two runs"
echo "slurm merge: by-hand tasks merged = one process; failed, stopped, lost, truncated, other-seed, other-scene and missing tasks named with one re-run command"
