#!/usr/bin/env bash
# Fails when a C++ source file passes MAX_LINES lines (800 by default): a file that long holds
# more than one purpose and is split by what it does (as jobs/h5/cube_*.cpp, the sweep parser's
# jobs/sweep_parse_*.cpp and solver/model/model_file_*.cpp are).
set -u
root=${1:?usage: check_file_size.sh SOURCE_ROOT [MAX_LINES]}
max=${2:-800}
cd "$root" || exit 2
status=0
largest=0
largest_file=
while IFS= read -r -d '' f; do
  n=$(wc -l <"$f")
  if [ "$n" -gt "$max" ]; then
    echo "file size: $f has $n lines; allowed: at most $max (split it by what it does)"
    status=1
  fi
  if [ "$n" -gt "$largest" ]; then largest=$n; largest_file=$f; fi
done < <(find solver records spectra jobs tests \( -name '*.h' -o -name '*.cpp' \) -print0 2>/dev/null)
[ $status -eq 0 ] && echo "file size: ok (largest: $largest_file, $largest lines)"
exit $status
