#!/usr/bin/env bash
# Fails when clang-format (pinned style in .clang-format) would change a tracked C++ file.
set -u
root=${1:?usage: check_format.sh SOURCE_ROOT CLANG_FORMAT}
fmt=${2:?usage: check_format.sh SOURCE_ROOT CLANG_FORMAT}
cd "$root" || exit 2
files=$(git ls-files '*.h' '*.cpp' 2>/dev/null || find solver records spectra jobs tests -name '*.h' -o -name '*.cpp')
bad=0
for f in $files; do
  "$fmt" --dry-run -Werror "$f" >/dev/null 2>&1 || { echo "format: $f"; bad=1; }
done
[ $bad -eq 0 ] && echo "format: ok"
exit $bad
