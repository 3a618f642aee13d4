#!/usr/bin/env bash
# C ABI smoke test: builds libaaglsd (release), writes the Rust core's output
# for testdata/castle1.png, compiles ffi/tests/smoke.c with gcc against the
# static and the shared library, and runs it. Two builds are tested:
#   std     `cargo build -p aaglsd-ffi --release` with the workspace's
#           default panic = "unwind": the library links std;
#   no_std  the same with panic = "abort": a no_std library that needs no
#           system library at all (what bare-metal targets always get).
# Both also run ffi/tests/sizes.c: the header's compile-time workspace sizes
# against the size functions. Honours CARGO_TARGET_DIR and CC. The header is
# not written here: `cargo run -p aaglsd-gen-header -- --check` checks it.
set -euo pipefail
cd "$(dirname "$0")/../.."

target_dir=$(cargo metadata --format-version 1 --no-deps |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
work=$target_dir/ffi-smoke
cc=${CC:-gcc}
cflags=(-std=c11 -Wall -Wextra -Werror -O2 -Iffi/include)

echo "==> expected output from the Rust core"
cargo run --quiet -p aaglsd-ffi --release --example smoke_expected -- "$work"

run_variant() {
    local name=$1
    shift # remaining arguments: extra cargo options
    local dir=$work/$name
    echo "==> libaaglsd ($name): cargo build -p aaglsd-ffi --release $*"
    cargo build --quiet -p aaglsd-ffi --release "$@"
    # The system libraries the staticlib needs (none for no_std).
    local libs
    libs=$(cargo rustc --quiet -p aaglsd-ffi --release "$@" --crate-type staticlib \
        -- --print native-static-libs 2>&1 | sed -n 's/.*native-static-libs: *//p' | tail -n 1)
    echo "    native-static-libs: ${libs:-(none)}"
    mkdir -p "$dir"
    cp "$target_dir/release/libaaglsd.a" "$target_dir/release/libaaglsd.so" "$dir/"
    # shellcheck disable=SC2086 # $libs is a list of linker flags
    "$cc" "${cflags[@]}" ffi/tests/smoke.c "$dir/libaaglsd.a" $libs -o "$dir/smoke_static"
    "$cc" "${cflags[@]}" ffi/tests/smoke.c -L"$dir" -laaglsd -Wl,-rpath,"$dir" \
        -o "$dir/smoke_shared"
    # shellcheck disable=SC2086
    "$cc" "${cflags[@]}" ffi/tests/sizes.c "$dir/libaaglsd.a" $libs -o "$dir/sizes"
    "$dir/sizes"
    for kind in static shared; do
        if "$dir/smoke_$kind" "$work/input.pgm" "$work/expected.txt"; then
            echo "ffi smoke ($name, $kind library): PASS"
        else
            echo "ffi smoke ($name, $kind library): FAIL" >&2
            return 1
        fi
    done
}

run_variant std
run_variant no_std --config 'profile.release.panic="abort"'
echo "ffi smoke: all PASS"
