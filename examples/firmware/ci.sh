#!/usr/bin/env bash
# Firmware check for CI (called from .ci/run), also fine to run by hand:
#   1. installs what is missing: the thumbv7em-none-eabihf target (rustup) and
#      qemu-system-arm (Debian's apt-get, non-interactive);
#   2. builds the firmware (UR5 FK, Jacobian, det in f64 and f32, IK; the Jaco's general
#      6R IK and the stack it takes) and the host check;
#      twice: the default closed-form IK with feature defmt (the UR5's solutions also
#      logged through kinegen's `defmt::Format`, decoded on the host), then the size-first
#      one (feature small-ik); the size-first UR5 `ik`'s flash at opt-level "s" checked
#      under 32 KiB (size.py); with FIRMWARE_OPT_Z=1 also the size-first one at "z";
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
    echo "installing qemu-system-arm (Debian)" >&2
    bash ../../.ci/apt_install.sh qemu-system-arm
fi
qemu-system-arm --version | head -n 1

host="$(rustc -vV | sed -n 's/^host: //p')"
target_dir="${CARGO_TARGET_DIR:-target}"

outputs="$(mktemp -d)"
trap 'rm -rf "$outputs"' EXIT

# Builds the firmware and the host check with the given features, runs the firmware on
# QEMU and checks its output, kept as "$outputs/$1".
run() {
    local name="$1"
    shift
    local features=("$@")
    # .cargo/config.toml sets the firmware target; the check is built for the host.
    cargo build --release --bin firmware "${features[@]}"
    cargo build --release --bin check --target "$host" "${features[@]}"
    local elf="$target_dir/thumbv7em-none-eabihf/release/firmware"
    local check="$target_dir/$host/release/check"
    local out="$outputs/$name" status=0
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
    # The ELF for the check's defmt decoding (feature `defmt`; unused without it).
    FIRMWARE_ELF="$elf" "$check" "$out"
}

# The default IK (the regular poses in lanes), then the size-first one (`small-ik`), at
# the profile's opt-level "s"; each bit-identical to the host built the same way, both with
# the same solutions. The default one is built with feature `defmt`: the same firmware and
# checks, plus its UR5 solutions logged through kinegen's `defmt::Format`, decoded on the
# host with the ELF and compared (src/defmt_log.rs). Without defmt it is the same code
# (the logging is behind the feature); a separate run cost CI two more release builds.
run lanes --features defmt
run small --features small-ik
"$target_dir/$host/release/check" --same-ik "$outputs/lanes" "$outputs/small"
# The size-first `ik` at the profile's opt-level "s" stays under 32 KiB (README.md,
# "Flash size"); size.py reads the symbols with the llvm-tools component.
if ! rustup component list --installed | grep -q '^llvm-tools'; then
    rustup component add llvm-tools
fi
python3 size.py --features small-ik --max-ik-f64 32768 | tail -n 1
# Opt-level "z" (README.md, "Flash size"), by hand: two more release builds.
if [ "${FIRMWARE_OPT_Z:-0}" = 1 ]; then
    CARGO_PROFILE_RELEASE_OPT_LEVEL=z run small-z --features small-ik
    "$target_dir/$host/release/check" --same-ik "$outputs/small" "$outputs/small-z"
fi
