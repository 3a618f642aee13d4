#!/usr/bin/env bash
# Builds the wasm module twice, for wasm32-unknown-unknown: the plain module
# and one with the simd128 target feature (LLVM vectorises what it can; the
# output is bit-identical, which wasm/tests/run.sh checks), and copies both
# to OUT_DIR as aaglsd_wasm.wasm and aaglsd_wasm_simd.wasm.
#   bash wasm/build.sh PROFILE OUT_DIR
# PROFILE: release (the node tests and the bench) or demo (release without
# debug info, stripped: what the demo serves). The simd build has a target
# directory of its own ($CARGO_TARGET_DIR/wasm-simd), so that the two
# RUSTFLAGS do not rebuild each other. Honours CARGO_TARGET_DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 2 ] || { echo "usage: wasm/build.sh release|demo OUT_DIR" >&2; exit 2; }
profile=$1
out=$2

target_dir=$(cargo metadata --format-version 1 --no-deps |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
rustup target list --installed | grep -qx wasm32-unknown-unknown ||
    rustup target add wasm32-unknown-unknown

args=(--quiet -p aaglsd-wasm --target wasm32-unknown-unknown)
case "$profile" in
    release) args+=(--release) ;;
    # A profile of its own, so that the debug-info-free module does not
    # evict the release build of the node test from the target directory.
    demo) args+=(--profile demo --config 'profile.demo.inherits="release"'
        --config 'profile.demo.debug=false' --config 'profile.demo.strip=true') ;;
    *) echo "wasm/build.sh: unknown profile $profile" >&2; exit 2 ;;
esac

mkdir -p "$out"
echo "==> cargo build ${args[*]}"
cargo build "${args[@]}"
cp "$target_dir/wasm32-unknown-unknown/$profile/aaglsd_wasm.wasm" "$out/aaglsd_wasm.wasm"
echo "==> RUSTFLAGS='-C target-feature=+simd128' cargo build ${args[*]}"
RUSTFLAGS="${RUSTFLAGS:-} -C target-feature=+simd128" CARGO_TARGET_DIR=$target_dir/wasm-simd \
    cargo build "${args[@]}"
cp "$target_dir/wasm-simd/wasm32-unknown-unknown/$profile/aaglsd_wasm.wasm" \
    "$out/aaglsd_wasm_simd.wasm"
for m in aaglsd_wasm aaglsd_wasm_simd; do
    echo "    $out/$m.wasm: $(wc -c <"$out/$m.wasm") bytes"
done
