#!/usr/bin/env bash
# needed_libraries.sh BINARY [--needs LIB]... [--not LIB]...
# Reads BINARY's dynamic section (readelf -d): every --needs prefix must be among its NEEDED
# libraries (so the check cannot pass on the wrong file) and no --not prefix may be. Used to
# prove that the replay program links no physics engine, no ray tracer and no importer's parser.
set -euo pipefail
binary=${1:?usage: needed_libraries.sh BINARY [--needs LIB]... [--not LIB]...}
shift
if [[ ! -f $binary ]]; then
  echo "needed_libraries: $binary: no such file" >&2
  exit 2
fi
needed=$(readelf -d "$binary" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
echo "$binary needs:" $needed
status=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --needs)
      if ! grep -q "^$2" <<< "$needed"; then
        echo "FAIL: $binary does not need $2 (expected it to)" >&2
        status=1
      fi
      shift 2 ;;
    --not)
      if hit=$(grep "^$2" <<< "$needed"); then
        echo "FAIL: $binary needs $hit (it must not)" >&2
        status=1
      fi
      shift 2 ;;
    *) echo "needed_libraries: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
[[ $status == 0 ]] && echo "ok"
exit $status
