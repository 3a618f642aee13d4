#!/usr/bin/env bash
# Builds the demo's files next to index.html: the wasm modules, plain and
# simd128 (wasm/build.sh demo: release without debug info), the JS wrapper
# and the bundled test image. Then serve the folder with any static server:
#   bash wasm/demo/build.sh
#   python3 -m http.server -d wasm/demo 8000     # open http://localhost:8000
# Honours CARGO_TARGET_DIR.
set -euo pipefail
cd "$(dirname "$0")/../.."

bash wasm/build.sh demo wasm/demo
# As .js: every static server sends that as JavaScript, which module
# scripts require (not all know .mjs).
cp wasm/js/aaglsd.mjs wasm/demo/aaglsd.js
cp testdata/castle1.png wasm/demo/
echo "wasm/demo: aaglsd_wasm.wasm ($(wc -c <wasm/demo/aaglsd_wasm.wasm) bytes)," \
    "aaglsd_wasm_simd.wasm ($(wc -c <wasm/demo/aaglsd_wasm_simd.wasm) bytes), aaglsd.js, castle1.png"
