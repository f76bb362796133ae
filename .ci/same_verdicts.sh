#!/usr/bin/env bash
# Runs the README's `cargo test --workspace --exclude kinegen-py` twice (the second run
# reuses the build) and fails unless both pass with the same verdict for every test. The
# verdicts are `binary: test: ok` lines taken from libtest's output, sorted.
set -uo pipefail
cd "$(dirname "$0")/.."
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

verdicts() { # log → "binary: test: verdict" lines, sorted
    awk '
        /^ *Running / { bin = $2 }
        /^ *Doc-tests / { bin = "doc-tests " $2 }
        /^test .* \.\.\. (ok|FAILED|ignored)/ {
            v = $NF; sub(/^test /, ""); sub(/ \.\.\. [^ ]*$/, "")
            print bin ": " $0 ": " v
        }' "$1" | sort
}

status=0
for run in 1 2; do
    echo "== cargo test --workspace --exclude kinegen-py, run $run"
    cargo test --workspace --exclude kinegen-py 2>&1 | tee "$out/log$run"
    code=${PIPESTATUS[0]}
    echo "== run $run: exit status $code"
    [ "$code" -eq 0 ] || status=1
    verdicts "$out/log$run" > "$out/verdicts$run"
done
if ! diff -u "$out/verdicts1" "$out/verdicts2"; then
    echo "error: the two runs of the test suite gave different verdicts (above)" >&2
    status=1
fi
count=$(wc -l < "$out/verdicts1")
if [ "$count" -eq 0 ]; then
    echo "error: no test verdicts found in the output" >&2
    status=1
fi
[ "$status" -eq 0 ] && echo "== both runs green, the same $count verdicts"
exit "$status"
