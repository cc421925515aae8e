#!/usr/bin/env bash
# The layer rules of docs/ARCHITECTURE.md, proved on the real build: each probe in tests/layering is an
# object library that links one layer exactly as that layer's own code does (tests/CMakeLists.txt). A
# probe that breaks a rule must fail to compile with the compiler's message for that rule, not any error;
# the probe that keeps the rules must compile, so the flags themselves are sound.
# Usage: check.sh BUILD_DIR
set -uo pipefail
build=$1
failed=0

build_probe() { cmake --build "$build" --target "$1" 2>&1; }

# name, then an extended regular expression the compiler's output must match
expect_rejected() {
  local target=$1 pattern=$2 out
  if out=$(build_probe "$target"); then
    echo "FAIL: $target compiled, but it breaks a layer rule"
    failed=1
  elif grep -Eq "$pattern" <<<"$out"; then
    echo "ok: $target rejected: $(grep -Em1 "$pattern" <<<"$out" | sed 's/^.*error: //')"
  else
    echo "FAIL: $target failed to compile, but not with /$pattern/:"
    echo "$out" | tail -20
    failed=1
  fi
}

if out=$(build_probe layering_game_includes_below); then
  echo "ok: layering_game_includes_below compiled"
else
  echo "FAIL: layering_game_includes_below (allowed includes only) does not compile:"
  echo "$out" | tail -20
  failed=1
fi
# GCC: "x.h: No such file or directory"; clang: "'x.h' file not found".
missing() { echo "($1: No such file or directory|'$1' file not found)"; }
expect_rejected layering_game_includes_session "$(missing session/session.h)"
expect_rejected layering_physics_includes_game "$(missing game/game_state.h)"
expect_rejected layering_ui_includes_app "$(missing app/frontend.h)"
expect_rejected layering_render_includes_platform "$(missing platform/glfw_window.h)"
expect_rejected layering_platform_includes_render "$(missing render/context.h)"
expect_rejected layering_game_includes_glew "gl\.h included before glew\.h"
expect_rejected layering_platform_includes_glew "gl\.h included before glew\.h"

# A quoted include with a ".." in its path leaves the including file's folder, and the compiler finds it
# beside that file whatever the layer's include roots: the sources are read for them instead. Prints
# "FILE:LINE: ..." for each one under the folders given.
relative_includes() { grep -rHEn --include='*.h' --include='*.cpp' --include='*.cc' '^\s*#\s*include\s*"([^"]*/)?\.\./' "$@"; }
here=$(cd "$(dirname "$0")" && pwd)
if out=$(relative_includes "$here/game_includes_relative.cc") && grep -q 'session/paths\.h' <<<"$out"; then
  echo "ok: a relative include that leaves its layer is found: ${out#"$here"/}"
else
  echo "FAIL: the scan missed the relative include of tests/layering/game_includes_relative.cc"
  failed=1
fi
if out=$(relative_includes "$here/../../src"); then
  echo "FAIL: relative includes leave their layer (include by the layer's root instead):"
  echo "$out"
  failed=1
else
  echo "ok: no relative include leaves its folder in src/"
fi
exit $failed
