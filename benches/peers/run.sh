#!/usr/bin/env bash
# One command for the peer comparison: installs the Python peers (NumPy, SciPy, SymPy) in a
# private venv, builds impactcheck and the Rust crate peer (benches/peers/rust_peer, its own
# package), runs everything in one script run and writes reports/performance.md.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
venv="$here/.venv"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$here/requirements.txt"
(cd "$root" && cargo build --release --quiet --bin impact --bin verify)
(cd "$here/rust_peer" && cargo build --release --quiet)
"$venv/bin/python" "$here/peers.py" --impact "$root/target/release/impact" \
  --verify "$root/target/release/verify" --rust-peer "$here/rust_peer/target/release/rust_peer" \
  --root "$root" --out "$root/reports" "$@"
