#!/usr/bin/env bash
# Build time of a crate that only invokes `kinegen::kinematics!` — what a user meets.
# Times `cargo build` after touching the crate (dependencies already built), best of 3,
# for each robot, in a default debug build (the proc-macro unoptimised) and with
# `[profile.dev.build-override] opt-level = 3`; an empty crate is the baseline.
#
#   scripts/build_time.sh [robot ...]      (default: planar_rr puma560 ur5 panda)
# A robot is a file of robots/ (ur5, or ur5_urdf: the UR5 from its URDF).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [ $# -gt 0 ]; then robots=("$@"); else robots=(planar_rr puma560 ur5 panda); fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

make_crate() { # dir, extra profile text
    mkdir -p "$1/src"
    cp "$root"/robots/*.toml "$1/"
    cp -r "$root"/robots/urdf "$1/"
    cat > "$1/Cargo.toml" <<TOML
[package]
name = "macro-user"
version = "0.1.0"
edition = "2021"

[dependencies]
kinegen = { path = "$root" }

[workspace]
$2
TOML
    echo 'pub struct Nothing;' > "$1/src/lib.rs"
    (cd "$1" && CARGO_TARGET_DIR="$1/target" cargo build -q)
}

best_of_3() { # dir
    local best=""
    for _ in 1 2 3; do
        touch "$1/src/lib.rs"
        local s e t
        s=$(date +%s%N)
        (cd "$1" && CARGO_TARGET_DIR="$1/target" cargo build -q)
        e=$(date +%s%N)
        t=$(((e - s) / 1000000))
        if [ -z "$best" ] || [ "$t" -lt "$best" ]; then best=$t; fi
    done
    echo "$best"
}

make_crate "$work/dbg" ""
make_crate "$work/opt" $'[profile.dev.build-override]\nopt-level = 3'
printf '%-12s %18s %28s\n' "robot" "debug (default) ms" "build-override opt-level=3 ms"
printf '%-12s %18s %28s\n' "(empty)" "$(best_of_3 "$work/dbg")" "$(best_of_3 "$work/opt")"
for r in "${robots[@]}"; do
    for d in dbg opt; do
        echo "kinegen::kinematics! { pub struct Robot = \"$r.toml\"; }" > "$work/$d/src/lib.rs"
    done
    printf '%-12s %18s %28s\n' "$r" "$(best_of_3 "$work/dbg")" "$(best_of_3 "$work/opt")"
done
