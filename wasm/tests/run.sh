#!/usr/bin/env bash
# wasm test: builds the module for wasm32-unknown-unknown (release), writes
# the host Rust core's output for testdata/castle1.png, and runs the node
# test (node >= 20, no npm packages). Honours CARGO_TARGET_DIR.
set -euo pipefail
cd "$(dirname "$0")/../.."

target_dir=$(cargo metadata --format-version 1 --no-deps |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')

echo "==> cargo build -p aaglsd-wasm --release --target wasm32-unknown-unknown"
cargo build --quiet -p aaglsd-wasm --release --target wasm32-unknown-unknown
wasm=$target_dir/wasm32-unknown-unknown/release/aaglsd_wasm.wasm
echo "    $wasm: $(wc -c <"$wasm") bytes"

echo "==> expected output from the host Rust core"
cargo run --quiet -p aaglsd-wasm --release --example wasm_expected -- "$target_dir/wasm-test"

echo "==> node --test wasm/tests/"
AAGLSD_WASM=$wasm AAGLSD_WASM_EXPECTED=$target_dir/wasm-test node --test wasm/tests/
