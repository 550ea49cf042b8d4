#!/bin/sh
# Creates target/numpy-venv (under the repository root) with numpy, for
# tests/reference/numpy_four_bar.py. Run from anywhere; prints the interpreter to use.
set -eu
root=$(CDPATH= cd -- "$(dirname -- "$0")/../.." && pwd)
venv="$root/target/numpy-venv"
python=${PYTHON:-python3}
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --upgrade pip
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check numpy
"$venv/bin/python" -c 'import numpy, sys; print("numpy", numpy.__version__, "on Python", sys.version.split()[0])'
echo "$venv/bin/python"
