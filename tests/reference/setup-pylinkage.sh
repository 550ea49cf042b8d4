#!/bin/sh
# Creates target/pylinkage-venv (under the repository root) with pylinkage 1.x, numba and scipy,
# for tests/reference/pylinkage_synthesis.py. Run from anywhere; prints the interpreter to use.
set -eu
root=$(CDPATH= cd -- "$(dirname -- "$0")/../.." && pwd)
venv="$root/target/pylinkage-venv"
python=${PYTHON:-python3}
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --upgrade pip
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check 'pylinkage>=1,<2' numba scipy numpy
"$venv/bin/python" -c 'import importlib.metadata as m, sys; print(" ".join(p + " " + m.version(p) for p in ("pylinkage", "numba", "scipy", "numpy")), "on Python", sys.version.split()[0])'
echo "$venv/bin/python"
