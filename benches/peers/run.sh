#!/usr/bin/env bash
# rodnet beside OpenSees and PyElastica (benches/peers/README.md). Not run in CI.
#   benches/peers/run.sh [cantilever] [timoshenko] [grid10] [grid20]      (default: all)
# Creates benches/peers/.venv on first use (openseespy, pyelastica, scipy from PyPI), builds
# rodnet in release mode if its binary is missing, runs the problems, prints the tables and
# writes benches/peers/out/{report.md,runs.csv,summary.csv} (or into $PEERS_OUT).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
venv="$here/.venv"

if [ ! -x "$venv/bin/python" ]; then
    "${PYTHON:-python3}" -m venv "$venv"
    "$venv/bin/pip" install --quiet -r "$here/requirements.txt"
fi

export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
if [ -z "${RODNET:-}" ] && [ ! -x "$CARGO_TARGET_DIR/release/rodnet" ]; then
    (cd "$root" && cargo build --release)
fi

# openseespy's Linux wheel loads its own BLAS, LAPACK and gfortran from openseespylinux/lib.
lib="$("$venv/bin/python" -c 'import importlib.util as u, pathlib as p; print(p.Path(u.find_spec("openseespylinux").origin).parent / "lib")')"
export LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

export PEERS_OUT="${PEERS_OUT:-$here/out}"
mkdir -p "$PEERS_OUT"
cd "$here"
"$venv/bin/python" -u peers.py "$@" | tee "$PEERS_OUT/report.md"
