#!/usr/bin/env bash
# The tree must be clean under clang-format and clang-tidy (configurations at the root). Needs the
# compile commands of the Release build (scripts/build.sh writes build/compile_commands.json).
# To fix formatting: clang-format-14 -i $(git ls-files '*.cpp' '*.h' '*.cc')
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t sources < <(git ls-files --cached --others --exclude-standard '*.cpp' '*.h' '*.cc')
echo "clang-format: ${#sources[@]} files"
clang-format-14 --dry-run -Werror "${sources[@]}"
# clang-tidy on every translation unit of the project (the fuzz targets build only with clang's
# fuzzer flags, which the g++ compile commands do not have; their headers are checked through the rest).
mapfile -t units < <(printf '%s\n' "${sources[@]}" | grep -E '^(src|tests)/.*\.cpp$' | grep -v '^tests/fuzz/')
echo "clang-tidy: ${#units[@]} files"
printf '%s\n' "${units[@]}" | xargs -P "$(nproc)" -n 4 clang-tidy-14 -p build --quiet 2>/dev/null
echo "style: clean"
