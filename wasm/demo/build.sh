#!/usr/bin/env bash
# Builds the demo's files next to index.html: the wasm module (release,
# without debug info), the JS wrapper and the bundled test image. Then serve
# the folder with any static server:
#   bash wasm/demo/build.sh
#   python3 -m http.server -d wasm/demo 8000     # open http://localhost:8000
# Honours CARGO_TARGET_DIR.
set -euo pipefail
cd "$(dirname "$0")/../.."

target_dir=$(cargo metadata --format-version 1 --no-deps |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
rustup target list --installed | grep -qx wasm32-unknown-unknown ||
    rustup target add wasm32-unknown-unknown
# A profile of its own, so that the debug-info-free module does not evict
# the release build of the node test from the target directory.
cargo build --quiet -p aaglsd-wasm --target wasm32-unknown-unknown --profile demo \
    --config 'profile.demo.inherits="release"' --config 'profile.demo.debug=false' \
    --config 'profile.demo.strip=true'
cp "$target_dir/wasm32-unknown-unknown/demo/aaglsd_wasm.wasm" wasm/demo/
# As .js: every static server sends that as JavaScript, which module
# scripts require (not all know .mjs).
cp wasm/js/aaglsd.mjs wasm/demo/aaglsd.js
cp testdata/castle1.png wasm/demo/
echo "wasm/demo: aaglsd_wasm.wasm ($(wc -c <wasm/demo/aaglsd_wasm.wasm) bytes), aaglsd.js, castle1.png"
