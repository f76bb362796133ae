#!/usr/bin/env bash
# `kinegen report` in a real browser (called from .ci/run; fine to run by hand from
# anywhere in the repository):
#   1. installs what is missing: Debian's chromium and chromium-driver (apt-get,
#      non-interactive), selenium and Pillow from PyPI into the Python venv under the
#      target dir (kinegen-py/ci.sh's, created here when absent);
#   2. writes the report of the UR5 (with its reachability map, `--reach 0.1`), the
#      PUMA 560 and the FANUC LR Mate 200iB URDF (with $KINEGEN_BIN when set, else a
#      debug build of the command);
#   3. loads each in headless Chromium (report_browser.py): fails on a console error, a
#      <math> not laid out as MathML, an empty <svg> or a blank screenshot.
# Screenshots and pages stay in $CARGO_TARGET_DIR/report-browser (never tracked files).
set -euo pipefail
cd "$(dirname "$0")/../.."

start=$SECONDS
target="${CARGO_TARGET_DIR:-target}"
venv="$target/py-venv"
out="$target/report-browser"

if ! command -v chromium >/dev/null 2>&1 || ! command -v chromedriver >/dev/null 2>&1; then
    echo "installing chromium and chromium-driver (Debian)" >&2
    bash .ci/apt_install.sh chromium chromium-driver
fi
chromium --version 2>/dev/null | head -n 1
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet selenium pillow
echo "report_browser.sh: browser and driver ready ($((SECONDS - start)) s)" >&2

# CI passes the debug binary the test suite built (KINEGEN_BIN); by hand it is built here.
kinegen="${KINEGEN_BIN:-}"
if [ -z "$kinegen" ]; then
    cargo build -q -p kinegen-cli --bin kinegen
    kinegen="$target/debug/kinegen"
fi
rm -rf "$out"
mkdir -p "$out"
"$kinegen" report ur5 --reach 0.1 -o "$out/ur5.html"
"$kinegen" report puma560 -o "$out/puma560.html"
"$kinegen" report robots/urdf/fanucLRMate200ib.urdf --tip tool0 -o "$out/fanuc_lrmate200ib.html"
"$venv/bin/python" kinegen-cli/tests/report_browser.py "$out" \
    "$out/ur5.html" "$out/puma560.html" "$out/fanuc_lrmate200ib.html"
echo "report_browser.sh: done in $((SECONDS - start)) s" >&2
