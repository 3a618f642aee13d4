#!/usr/bin/env bash
# The wasm timing bench: builds the plain and simd128 modules (wasm/build.sh
# release) and the native example (wasm/examples/wasm_bench_native.rs), then
# runs `node wasm/bench/bench.mjs [IMAGE...]` (default: the York Urban .jpg
# images of ../shared/data/yorkurban). AAGLSD_BENCH_REPS sets the runs per
# image (default 7); AAGLSD_BENCH_CHROMIUM=/usr/bin/chromium adds headless
# Chromium's times (puppeteer-core from wasm/demo/test: run
# wasm/demo/test/run.sh once). Honours CARGO_TARGET_DIR. Run it on a quiet
# machine: the bench prints the load average before and after.
set -euo pipefail
cd "$(dirname "$0")/../.."

source wasm/modules.sh
echo "==> cargo build -p aaglsd-wasm --release --example wasm_bench_native"
cargo build --quiet -p aaglsd-wasm --release --example wasm_bench_native

echo "==> node wasm/bench/bench.mjs $*"
AAGLSD_WASM=$modules/aaglsd_wasm.wasm AAGLSD_WASM_SIMD=$modules/aaglsd_wasm_simd.wasm \
    AAGLSD_BENCH_NATIVE=$target_dir/release/examples/wasm_bench_native \
    AAGLSD_BENCH_WORK=$target_dir/wasm-bench node wasm/bench/bench.mjs "$@"
