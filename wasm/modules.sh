# Sourced from the repository root by wasm/tests/run.sh and wasm/bench/run.sh:
# sets target_dir (cargo's, honouring CARGO_TARGET_DIR) and modules (the
# directory of the release modules, plain and simd128), and builds them.
target_dir=$(cargo metadata --format-version 1 --no-deps |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
modules=$target_dir/wasm-modules/release
bash wasm/build.sh release "$modules"
