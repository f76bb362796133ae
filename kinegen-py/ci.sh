#!/usr/bin/env bash
# The Python module's check, from the repository root: a fresh virtual environment under
# target/ (maturin, numpy, pytest from PyPI; nothing preinstalled assumed but python3 with
# venv and pip), the wheel built (dev profile, see below) and installed, then pytest.
#
#   bash kinegen-py/ci.sh
#
# `maturin build` + `pip install` of the wheel rather than `maturin develop`: it tests the
# wheel as users get it (the same abi3 file), at the same cost — both are one build
# (measured on 2 cores, 2026-12-05: when nothing changed, 2.3 s to build and install the
# wheel, 2.5 s to develop).
# Exits non-zero on any failure.
set -euo pipefail

cd "$(dirname "$0")/.."
root="$PWD"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}"
venv="$CARGO_TARGET_DIR/py-venv"
wheels="$CARGO_TARGET_DIR/py-wheels"
python="${PYTHON:-python3}"

start=$SECONDS
stamp() { echo "kinegen-py/ci.sh: $1 ($((SECONDS - start)) s so far)"; }

rm -rf "$venv" "$wheels"
if ! "$python" -m venv "$venv"; then
    # Debian splits venv out of python3 (python3-venv); install it where we may.
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        rm -rf "$venv"
        apt-get update -qq && apt-get install -y -qq python3-venv
        "$python" -m venv "$venv"
    else
        echo "kinegen-py/ci.sh: $python -m venv failed (on Debian: apt-get install python3-venv)" >&2
        exit 1
    fi
fi
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet maturin numpy pytest
stamp "virtual environment ready"

# The dev profile (the workspace's: engine, runtime and CLI optimised, the bindings not):
# the same code and the same values as a release wheel (no fast-math either way), built in
# 176 s in CI on 2 cores, where the release wheel took 233 s and 295 s in the two runs
# before; the benchmarks (bench/) build release wheels.
"$venv/bin/maturin" build --quiet -m kinegen-py/Cargo.toml -o "$wheels"
stamp "wheel built"

"$venv/bin/python" -m pip install --quiet --no-deps "$wheels"/kinegen-*.whl
stamp "wheel installed"

# The generated Rust code's values, which tests/test_generated_rust.py compares with.
# KINEGEN_REFERENCE_VALUES may name a binary of that example already built (CI passes the
# test suite's, which `cargo run` would rebuild: it resolves the robots crate's features
# apart from the workspace's); otherwise it is built here.
if [ -x "${KINEGEN_REFERENCE_VALUES:-}" ]; then
    "$KINEGEN_REFERENCE_VALUES" > "$CARGO_TARGET_DIR/rust-values.json"
else
    cargo run --quiet -p kinegen-robots --example reference_values > "$CARGO_TARGET_DIR/rust-values.json"
fi
stamp "generated Rust values written"

# From outside the source tree, so the installed package is the one imported. A test
# skipped here would be one not run: that fails the check.
log="$CARGO_TARGET_DIR/py-tests.log"
status=0
(cd "$venv" && KINEGEN_RUST_VALUES="$CARGO_TARGET_DIR/rust-values.json" \
    "$venv/bin/python" -m pytest -q -rs -p no:cacheprovider "$root/kinegen-py/tests") \
    > "$log" 2>&1 || status=$?
cat "$log"
if [ "$status" != 0 ]; then
    exit "$status"
fi
if grep -q "SKIPPED" "$log"; then
    echo "kinegen-py/ci.sh: a test was skipped (see above)" >&2
    exit 1
fi
stamp "tests passed"
