#!/usr/bin/env python3
"""Flash size of the generated UR5 functions (and the Jaco's general 6R `ik`) in the firmware ELF.

Builds the firmware (release profile of Cargo.toml: opt-level "s", LTO, one codegen unit;
`--opt-level 3` overrides the level), then reads symbol sizes with `llvm-nm` and call
targets with `llvm-objdump` (from `rustup component add llvm-tools`) and prints a
Markdown table: each wrapper `ur5_<method>_<f64|f32>` (in src/main.rs, never inlined, so
its size is the generated method's code), then the library routines each precision
reaches through calls (libm's sin/cos, compiler-builtins' soft-float f64), counted once
per precision.

    python3 size.py [--opt-level s|z|1|2|3] [--features small-ik] [--max-ik-f64 BYTES]

`--max-ik-f64`: exit with status 1 when the UR5's f64 `ik` adds more than BYTES (ci.sh
holds the size-first path under 32 KiB this way).
"""
import argparse
import os
import re
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
METHODS = ["fk", "jacobian", "jacobian_det"]


def tool(name):
    libdir = subprocess.run(["rustc", "--print", "target-libdir"], check=True,
                            capture_output=True, text=True).stdout.strip()
    path = Path(libdir).parent / "bin" / name
    if not path.exists():
        sys.exit(f"{path} not found: run `rustup component add llvm-tools`")
    return str(path)


def build(opt_level, features):
    env = dict(os.environ)
    env["CARGO_PROFILE_RELEASE_OPT_LEVEL"] = opt_level
    subprocess.run(["cargo", "build", "--release", "--bin", "firmware"]
                   + (["--features", features] if features else []), cwd=HERE,
                   env=env, check=True)
    target_dir = env.get("CARGO_TARGET_DIR", str(HERE / "target"))
    return Path(target_dir) / "thumbv7em-none-eabihf" / "release" / "firmware"


def sizes(elf):
    out = subprocess.run([tool("llvm-nm"), "--print-size", "--radix=d", elf], check=True,
                         capture_output=True, text=True).stdout
    s = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[2].lower() == "t":
            s[parts[3]] = int(parts[1])
    return s


def calls(elf):
    """Function → set of functions it calls or tail-calls."""
    out = subprocess.run([tool("llvm-objdump"), "-d", "--no-show-raw-insn", elf],
                         check=True, capture_output=True, text=True).stdout
    graph, current = {}, None
    head = re.compile(r"^[0-9a-f]+ <(.+)>:$")
    call = re.compile(r"\s(?:bl|blx|b|b\.w)\s+0x[0-9a-f]+ <([^>+]+)>")
    for line in out.splitlines():
        m = head.match(line)
        if m:
            current = m.group(1)
            graph.setdefault(current, set())
            continue
        m = call.search(line)
        if m and current and m.group(1) != current:
            graph[current].add(m.group(1))
    return graph


def reach(graph, roots):
    seen, todo = set(), list(roots)
    while todo:
        f = todo.pop()
        for g in graph.get(f, ()):
            if g not in seen and g not in roots:
                seen.add(g)
                todo.append(g)
    return seen


def short(sym):
    m = re.search(r"libm4math(\d+)", sym)
    if m:  # legacy mangling: length-prefixed module name, then the function's
        rest = sym[m.end():]
        rest = rest[int(m.group(1)):]
        n = re.match(r"\d+", rest).group(0)
        return "libm::" + rest[len(n):len(n) + int(n)]
    m = re.search(r"(__\w+?)$", sym)
    return m.group(1) if m else sym


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--opt-level", default="s")
    ap.add_argument("--features", default="", help="e.g. small-ik")
    ap.add_argument("--max-ik-f64", type=int, default=None,
                    help="fail if the UR5's f64 ik adds more than this many bytes")
    args = ap.parse_args()
    elf = build(args.opt_level, args.features)
    size, graph = sizes(elf), calls(elf)
    print(f"\nUR5, thumbv7em-none-eabihf, release, opt-level \"{args.opt_level}\", LTO; bytes of .text\n")
    print("| function | f64 (soft-float) | f32 (FPU) |")
    print("|---|---:|---:|")
    total = {"f64": 0, "f32": 0}
    for m in METHODS:
        row = []
        for p in ("f64", "f32"):
            n = size.get(f"ur5_{m}_{p}", 0)
            total[p] += n
            row.append(str(n))
        print(f"| `{m}` | {row[0]} | {row[1]} |")
    print(f"| **sum of the three** | **{total['f64']}** | **{total['f32']}** |")
    helpers = {}
    for p in ("f64", "f32"):
        roots = {f"ur5_{m}_{p}" for m in METHODS}
        helpers[p] = sorted(reach(graph, roots), key=lambda s: -size.get(s, 0))
        n = sum(size.get(s, 0) for s in helpers[p])
        print(f"| routines called (once per precision) | " if p == "f64" else "", end="")
        helpers[p + "_n"] = n
    print(f"{helpers['f64_n']} | {helpers['f32_n']} |")
    print(f"| **total** | **{total['f64'] + helpers['f64_n']}** | **{total['f32'] + helpers['f32_n']}** |")
    for p in ("f64", "f32"):
        listed = ", ".join(f"{short(s)} {size.get(s, 0)}" for s in helpers[p])
        print(f"\n{p} routines: {listed}")
    # The closed-form IK, f64 and f32 (the f32 one solves in f64): each wrapper, and what it
    # reaches beyond the three methods' routines of its precision above (the subproblem
    # solvers, `finish`, the residual check, …); and what both share.
    reached, added = {}, {}
    for p in ("f64", "f32"):
        ik_root = f"ur5_ik_{p}"
        if ik_root not in size:
            continue
        seen = set(helpers[p]) | {f"ur5_{m}_{p}" for m in METHODS}
        own = sorted(reach(graph, {ik_root}) - seen - {ik_root}, key=lambda s: -size.get(s, 0))
        reached[p] = set(own)
        n_own = sum(size.get(s, 0) for s in own)
        print(f"\n| `ik` ({p}, all solutions) | bytes |\n|---|---:|")
        print(f"| wrapper `{ik_root}` | {size[ik_root]} |")
        print(f"| routines only `ik` reaches | {n_own} |")
        print(f"| **total added by `ik`** | **{size[ik_root] + n_own}** |")
        added[p] = size[ik_root] + n_own
        print(f"\n{p} ik routines: " + ", ".join(f"{short(s)} {size.get(s, 0)}" for s in own))
    if len(reached) == 2:
        shared = reached["f64"] & reached["f32"]
        print(f"\nroutines both `ik`s reach (counted in both totals above): "
              f"{sum(size.get(s, 0) for s in shared)} bytes")
    # The Jaco's general 6R `ik` (f64): its wrapper and everything it reaches, and the part
    # the UR5's f64 methods and `ik` do not reach already.
    root = "jaco_ik_f64"
    if root in size:
        everything = reach(graph, {root}) - {root}
        ur5 = reach(graph, {f"ur5_{m}_f64" for m in METHODS} | {"ur5_ik_f64"}) | {
            f"ur5_{m}_f64" for m in METHODS} | {"ur5_ik_f64"}
        own = sorted(everything - ur5, key=lambda s: -size.get(s, 0))
        n_all = size[root] + sum(size.get(s, 0) for s in everything)
        n_own = size[root] + sum(size.get(s, 0) for s in own)
        print(f"\n| Jaco `ik` (f64, general 6R) | bytes |\n|---|---:|")
        print(f"| wrapper `{root}` | {size[root]} |")
        print(f"| with every routine it reaches | {n_all} |")
        print(f"| **of which the UR5's code above does not reach** | **{n_own}** |")
        print(f"\nJaco ik routines: " + ", ".join(f"{short(s)} {size.get(s, 0)}" for s in own[:25]))
    print(f"\nwhole image: {subprocess.run([tool('llvm-size'), elf], capture_output=True, text=True).stdout.strip()}")
    if args.max_ik_f64 is not None:
        n = added.get("f64")
        if n is None or n > args.max_ik_f64:
            sys.exit(f"size: the UR5's f64 `ik` adds {n} bytes, over the {args.max_ik_f64} allowed")
        print(f"size: the UR5's f64 `ik` adds {n} bytes, within {args.max_ik_f64}")


if __name__ == "__main__":
    main()
