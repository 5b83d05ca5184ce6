#!/usr/bin/env bash
# sample_scenes' progress line: shown on a pseudo-terminal (script(1) from util-linux) for a run
# of over a second whose scenes go to a file, not when stderr is a pipe, forced by --progress
# and stopped by --no-progress; the scenes on stdout and in an .npz file are the same each time.
#   test/cli_progress.sh SAMPLE_SCENES SOURCE_DIR
set -euo pipefail
bin="$1"
src="$2"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# 100 simulated scenes of the default table on one thread: a few seconds.
args="--config $src/config/default.yaml --seed 3 --scenes 100 --physics check --threads 1"
fail() { echo "FAIL: $*" >&2; exit 1; }

# On a terminal: the line rewritten in place, its final state on a line of its own.
script -qefc "$bin $args > $dir/tty.jsonl" /dev/null </dev/null >"$dir/tty.err"
grep -q $'\rsample_scenes: [0-9]*/100 scenes (' "$dir/tty.err" || fail "no progress line on a terminal"
grep -q 'sample_scenes: 100/100 scenes (100.0 %), [0-9]* scenes/s, 0 failed, ETA 0:00:00' \
  "$dir/tty.err" || fail "no final progress line: $(tr '\r' '\n' <"$dir/tty.err" | tail -n 2)"
# --no-progress on the same terminal: nothing.
script -qefc "$bin $args --no-progress > $dir/quiet.jsonl" /dev/null </dev/null >"$dir/quiet.err"
[ ! -s "$dir/quiet.err" ] || fail "--no-progress printed: $(cat "$dir/quiet.err")"

# In a pipe: nothing on stderr; the same scenes.
# shellcheck disable=SC2086
"$bin" $args 2>"$dir/pipe.err" | cat >"$dir/pipe.jsonl"
[ ! -s "$dir/pipe.err" ] || fail "stderr in a pipe is not empty: $(cat "$dir/pipe.err")"
cmp -s "$dir/tty.jsonl" "$dir/pipe.jsonl" || fail "stdout differs with the progress line"
cmp -s "$dir/quiet.jsonl" "$dir/pipe.jsonl" || fail "stdout differs with --no-progress"
[ "$(wc -l <"$dir/pipe.jsonl")" -eq 100 ] || fail "expected 100 scenes"

# --progress in a pipe: one line at a time, the last one complete; the .npz file the same.
# shellcheck disable=SC2086
"$bin" $args --output "$dir/plain.npz" 2>"$dir/plain.err"
# shellcheck disable=SC2086
"$bin" $args --output "$dir/forced.npz" --progress 2>"$dir/forced.err"
[ ! -s "$dir/plain.err" ] || fail "--output without a terminal printed: $(cat "$dir/plain.err")"
tail -n 1 "$dir/forced.err" | grep -q '^sample_scenes: 100/100 scenes (100.0 %), ' ||
  fail "--progress: $(cat "$dir/forced.err")"
if grep -q $'\r' "$dir/forced.err"; then fail "--progress in a pipe rewrote its line"; fi
cmp -s "$dir/plain.npz" "$dir/forced.npz" || fail "the .npz differs with --progress"
echo "progress line: on a terminal, not in a pipe; outputs unchanged"
