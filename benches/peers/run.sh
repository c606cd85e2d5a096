#!/usr/bin/env bash
# One command for the peer comparison: installs the Python peers in a private venv, builds the
# Rust side, runs both in one script run and writes reports/performance.md.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
venv="$here/.venv"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$here/requirements.txt"
(cd "$root" && cargo build --release --quiet --bin impact)
"$venv/bin/python" "$here/peers.py" --impact "$root/target/release/impact" --out "$root/reports" "$@"
