#!/usr/bin/env bash
# The README's two commands share one build: `scripts/test.sh` after `scripts/quickstart.sh`
# compiles nothing. Both build with plain `scripts/build.sh` (same folder, same flags, -Werror):
# this checks that from their text, then runs that build once more right after one and fails
# if ninja finds anything to do (a generated file rewritten on each configure, a flag that
# differs between the two, ...), naming what it would rebuild.
#   scripts/check-rebuild.sh        (after scripts/test.sh or scripts/quickstart.sh has built)
set -euo pipefail
cd "$(dirname "$0")/.."
grep -qx 'scripts/build.sh' scripts/quickstart.sh || {
  echo "check-rebuild: scripts/quickstart.sh does not build with plain scripts/build.sh" >&2
  exit 1
}
grep -qx '  scripts/build.sh "$@"' scripts/test.sh || {
  echo "check-rebuild: scripts/test.sh does not build with scripts/build.sh \"\$@\"" >&2
  exit 1
}
output=$(scripts/build.sh 2>&1)
if ! grep -q '^ninja: no work to do' <<<"$output"; then
  echo "check-rebuild: a second scripts/build.sh compiled again:" >&2
  grep -E '^\[[0-9]+/[0-9]+\]' <<<"$output" | head -20 >&2
  exit 1
fi
echo "check-rebuild: a second scripts/build.sh had nothing to do"
