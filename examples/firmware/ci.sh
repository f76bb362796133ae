#!/usr/bin/env bash
# Firmware check for CI (called from .ci/run), also fine to run by hand:
#   1. installs what is missing: the thumbv7em-none-eabihf target (rustup) and
#      qemu-system-arm (Debian's apt-get, non-interactive);
#   2. builds the firmware (UR5 FK, Jacobian, det in f64 and f32) and the host check;
#   3. runs the firmware on QEMU's mps2-an386 (Cortex-M4F) with a time limit, its
#      semihosting output piped into the host check, which compares every value with the
#      host's (see src/bin/check.rs). Exit status 0 only if all of it succeeded.
set -euo pipefail
cd "$(dirname "$0")"

# QEMU must never hang CI: the firmware exits QEMU itself in well under a second.
QEMU_TIMEOUT="${QEMU_TIMEOUT:-60}"

if ! rustup target list --installed | grep -qx thumbv7em-none-eabihf; then
    rustup target add thumbv7em-none-eabihf
fi
if ! command -v qemu-system-arm >/dev/null 2>&1; then
    sudo=""
    if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
    echo "installing qemu-system-arm (Debian)" >&2
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -qq
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
        qemu-system-arm </dev/null
fi
qemu-system-arm --version | head -n 1

host="$(rustc -vV | sed -n 's/^host: //p')"
# .cargo/config.toml sets the firmware target; the check is built for the host.
cargo build --release --bin firmware
cargo build --release --bin check --target "$host"
target_dir="${CARGO_TARGET_DIR:-target}"
elf="$target_dir/thumbv7em-none-eabihf/release/firmware"
check="$target_dir/$host/release/check"

out="$(mktemp)"
trap 'rm -f "$out"' EXIT
status=0
timeout "$QEMU_TIMEOUT" qemu-system-arm -M mps2-an386 -cpu cortex-m4 \
    -display none -monitor none -serial none \
    -semihosting-config enable=on,target=native \
    -kernel "$elf" </dev/null >"$out" || status=$?
if [ "$status" = 124 ]; then
    echo "firmware: QEMU did not exit within ${QEMU_TIMEOUT}s" >&2
fi
if [ "$status" != 0 ]; then
    echo "firmware: QEMU exited with status $status; output:" >&2
    cat "$out" >&2
    exit 1
fi
"$check" "$out"
