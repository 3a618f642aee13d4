#!/usr/bin/env bash
# wasm test: builds the module for wasm32-unknown-unknown (release), plain
# and with simd128 (wasm/build.sh), writes the host Rust core's output for
# testdata/castle1.png, and runs the node tests (node >= 20, no npm
# packages) on each module. Honours CARGO_TARGET_DIR.
set -euo pipefail
cd "$(dirname "$0")/../.."

source wasm/modules.sh

echo "==> expected output from the host Rust core"
cargo run --quiet -p aaglsd-wasm --release --example wasm_expected -- "$target_dir/wasm-test"

# Every test, the bit-exact ones included, runs on both modules.
for kind in plain simd; do
    wasm=$modules/aaglsd_wasm.wasm
    [ "$kind" = simd ] && wasm=$modules/aaglsd_wasm_simd.wasm
    echo "==> node --test wasm/tests/ ($kind: $wasm)"
    AAGLSD_WASM=$wasm AAGLSD_WASM_KIND=$kind AAGLSD_WASM_MODULES=$modules \
        AAGLSD_WASM_EXPECTED=$target_dir/wasm-test \
        node --test wasm/tests/
done
