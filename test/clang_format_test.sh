#!/usr/bin/env bash
# Fails when a C++ file of the package is not laid out as its .clang-format says, and names the
# files: test/clang_format_test.sh CLANG_FORMAT PACKAGE_DIR
# Fix with: clang-format -i FILE...
set -euo pipefail
clang_format=$1
cd "$2"
mapfile -t files < <(find src include test benchmarks -name '*.cpp' -o -name '*.hpp' | sort)
bad=()
for f in "${files[@]}"; do
  "$clang_format" --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "not formatted with $("$clang_format" --version): ${bad[*]}" >&2
  exit 1
fi
echo "${#files[@]} files formatted"
