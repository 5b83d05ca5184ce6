#!/usr/bin/env bash
# sample_scenes ... | sample_scenes --validate -: for every shipped configuration and the
# robosuite test ones, in each collision mode, the scenes that were placed are valid and the
# failed ones are not: as many "valid": false verdicts as "success": false scenes, one verdict
# per scene, and the same exit status (0 all placed / valid, 1 otherwise).
#   test/validate_round_trip.sh SAMPLE_SCENES SOURCE_DIR [SCENES]
set -uo pipefail
bin="$1"
source_dir="$2"
scenes="${3:-200}"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$source_dir" || exit 2
# package:// paths of the configurations resolve to this checkout.
export ROS_PACKAGE_PATH="$PWD${ROS_PACKAGE_PATH:+:$ROS_PACKAGE_PATH}"
fail=0
for config in config/*.yaml test/data/robosuite/*.yaml; do
  for mode in radius fcl radius_and_fcl; do
    args=(--config "$config" --collision-check "$mode")
    "$bin" "${args[@]}" --seed 3 --scenes "$scenes" > "$dir/scenes.jsonl" 2> /dev/null
    sampled=$?
    "$bin" "${args[@]}" --validate - < "$dir/scenes.jsonl" > "$dir/verdicts.jsonl"
    validated=$?
    failed=$(grep -c '"success": false' "$dir/scenes.jsonl")
    invalid=$(grep -c '^{"scene": [0-9]*, "valid": false' "$dir/verdicts.jsonl")
    lines=$(wc -l < "$dir/verdicts.jsonl")
    if [ "$sampled" -gt 1 ] || [ "$validated" != "$sampled" ] || [ "$invalid" != "$failed" ] ||
       [ "$lines" != "$scenes" ]; then
      echo "FAIL: $config $mode: sampling status $sampled, $failed failed; validation status" \
           "$validated, $invalid invalid of $lines verdicts"
      grep -m 2 '"valid": false' "$dir/verdicts.jsonl" | cut -c1-600
      fail=1
    else
      echo "ok: $config $mode: $lines verdicts, $invalid invalid = $failed failed"
    fi
  done
done
exit $fail
