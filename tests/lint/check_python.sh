#!/usr/bin/env bash
# Fails when pyflakes (Debian's python3-pyflakes under /usr/bin/python3) reports a tracked Python
# file: the *.py files and the scripts without a suffix whose first line names python. pyflakes
# finds what runs wrong or not at all without running it: undefined names, names imported or
# assigned and never used, redefinitions, f-strings without fields, format strings that do not
# match their arguments. Python embedded in shell scripts (heredocs) is not checked.
set -u
root=${1:?usage: check_python.sh SOURCE_ROOT}
cd "$root" || exit 2
if ! /usr/bin/python3 -c "import pyflakes" 2>/dev/null; then
  echo "pyflakes: /usr/bin/python3 has no pyflakes module (bash scripts/setup.sh installs python3-pyflakes)"
  exit 1
fi
files=$(git ls-files 2>/dev/null || find . -path ./build -prune -o -type f -print | sed 's|^\./||')
python=()
for f in $files; do
  case "$f" in
    *.py) python+=("$f") ;;
    */*.*) ;;
    *) [ -f "$f" ] && head -n 1 "$f" | grep -q '^#!.*python' && python+=("$f") ;;
  esac
done
if [ ${#python[@]} -eq 0 ]; then
  echo "pyflakes: no Python file found under $root"
  exit 1
fi
/usr/bin/python3 -m pyflakes "${python[@]}" && echo "pyflakes: ${#python[@]} files ok"
