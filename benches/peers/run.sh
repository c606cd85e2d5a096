#!/usr/bin/env bash
# One command for the peer comparison: installs the Python peers (NumPy, SciPy, SymPy) in a
# private venv and the C libraries the russell_ode peer links (Debian's packages), builds
# impactcheck and the two Rust crate peers (benches/peers/rust_peer and russell_peer, each its
# own package), runs everything in one script run and writes reports/performance.md.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
venv="$here/.venv"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$here/requirements.txt"
debs="liblapacke-dev libopenblas-dev libmumps-seq-dev libsuitesparse-dev"
missing=""
for d in $debs; do dpkg -s "$d" >/dev/null 2>&1 || missing="$missing $d"; done
if [ -n "$missing" ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "run.sh: the russell_ode peer needs Debian's$missing; install them (as root: apt-get install$missing)" >&2
    exit 2
  fi
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing
fi
(cd "$root" && cargo build --release --quiet --bin impact --bin verify)
(cd "$here/rust_peer" && cargo build --release --quiet)
(cd "$here/russell_peer" && cargo build --release --quiet)
"$venv/bin/python" "$here/peers.py" --impact "$root/target/release/impact" \
  --verify "$root/target/release/verify" --rust-peer "$here/rust_peer/target/release/rust_peer" \
  --russell-peer "$here/russell_peer/target/release/russell_peer" \
  --root "$root" --out "$root/reports" "$@"
