#!/usr/bin/env bash
# Hairer's RADAU5 and DOP853 (Fortran 77) against impactcheck's, same machine, same run; writes the
# `hairer` block of reports/performance.md.
#
# usage: bash benches/peers/hairer/run.sh HWODE_DIR [hairer.py options]
#   HWODE_DIR holds radau5.f, dc_decsol.f, decsol.f, dop853.f and hinit.f of
#   https://github.com/cpmech/hwode (Hairer's codes; not committed here: clone it, or take the five
#   files out of any snapshot with `git show HEAD:radau5.f` etc.). Needs gfortran (Debian: gfortran).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
if [ $# -lt 1 ] || [ ! -d "$1" ]; then
  echo "usage: bash benches/peers/hairer/run.sh HWODE_DIR [--repeats N --rounds N]" >&2
  exit 2
fi
src="$(cd "$1" && pwd)"
shift
for f in radau5.f dc_decsol.f decsol.f dop853.f hinit.f; do
  [ -f "$src/$f" ] || { echo "run.sh: $src/$f is missing (see the usage at the top of this file)" >&2; exit 2; }
done
command -v gfortran >/dev/null || { echo "run.sh: gfortran is missing (apt-get install gfortran)" >&2; exit 2; }
build="$root/target/hairer"
mkdir -p "$build"
gfortran -O3 -march=native -std=legacy -w -J "$build" -o "$build/driver" "$here/driver.f90" \
  "$src/radau5.f" "$src/dc_decsol.f" "$src/decsol.f" "$src/dop853.f" "$src/hinit.f"
(cd "$root" && cargo build --release --quiet --bin impact)
python3 "$here/hairer.py" --impact "$root/target/release/impact" --driver "$build/driver" \
  --out "$root/reports" "$@"
