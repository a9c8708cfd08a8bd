#!/usr/bin/env bash
# Where DER's O(h²) error constant comes from on the clamped cantilever (docs/performance.md,
# "Accuracy per unknown: where the constant comes from"). Not run by CI: it installs numpy and
# scipy in benches/accuracy/.venv. Usage: bash benches/accuracy/run.sh (after cargo build --release);
# RODNET=path/to/rodnet to measure another binary; outputs in $RUNS (default /tmp/rodnet-accuracy).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here"
[ -x .venv/bin/python ] || { python3 -m venv .venv && .venv/bin/pip install -q numpy scipy; }
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
py=.venv/bin/python
runs="${RUNS:-/tmp/rodnet-accuracy}"
mkdir -p "$runs"
$py elastica.py                                   # references, checked against Bisshopp–Drucker
$py sweep_rodnet.py | tee "$runs/sweep_rodnet.txt"  # rodnet's constants C = e·N², N = 10 … 320
$py probe_moment.py | tee "$runs/probe_moment.txt"  # the moment law of rodnet's curvature measure
for k in sin tan; do $py match_rodnet.py $k | tee "$runs/match_$k.txt"; done  # the Python model against rodnet
$py decompose.py | tee "$runs/decompose.txt"        # curvature measures × end weights
$py linear_limit.py | tee "$runs/linear_limit.txt"
