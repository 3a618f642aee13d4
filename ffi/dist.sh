#!/usr/bin/env bash
# The C library's distributable: a folder that a C team uses with only a C
# cross compiler and CMake (no Rust).
#
#   bash ffi/dist.sh DIR
#   AAGLSD_DIST_TARGETS="thumbv7em-none-eabihf" bash ffi/dist.sh DIR   # fewer targets
#   AAGLSD_DIST_PROFILE=dist-speed bash ffi/dist.sh DIR   # opt-level 3 instead of z
#
# Writes:
#   DIR/include/aaglsd.h                       the committed header
#   DIR/lib/<rust-target>/libaaglsd.a          one archive per target, built for size
#                                              (profile `dist`: opt-level z, fat LTO, one
#                                              codegen unit, no debug info; then debug
#                                              sections stripped)
#   DIR/lib/cmake/aaglsd/aaglsdConfig.cmake    find_package(aaglsd): imported target
#                                              aaglsd::aaglsd, archive picked from the
#                                              compiler's core and float ABI
#   DIR/lib/cmake/aaglsd/aaglsdConfigVersion.cmake
#   DIR/LICENSE-MIT, DIR/LICENSE-APACHE, DIR/THIRD-PARTY.txt (the crates in the archives)
#   DIR/README.md                              ffi/dist/README.md: how to link it
#
# Installs the rustup targets it needs when missing. Builds into the
# workspace's target directory (honours CARGO_TARGET_DIR); DIR is replaced.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
[ $# -eq 1 ] || {
    echo "usage: bash ffi/dist.sh DIR" >&2
    exit 2
}
mkdir -p "$1"
dist="$(cd "$1" && pwd)"
cd "$root"

targets=${AAGLSD_DIST_TARGETS:-"thumbv6m-none-eabi thumbv7em-none-eabi thumbv7em-none-eabihf thumbv8m.main-none-eabihf riscv32imc-unknown-none-elf"}
installed=$(rustup target list --installed)
for t in $targets; do
    grep -qx "$t" <<<"$installed" || rustup target add "$t"
done

target_dir=$(cargo metadata --format-version 1 --no-deps |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
# llvm-objcopy as shipped with every Rust toolchain (it reads every target's
# objects; the C cross binutils each read one architecture).
sysroot=$(rustc --print sysroot)
host=$(rustc -vV | sed -n 's/^host: //p')
objcopy() { LD_LIBRARY_PATH="$sysroot/lib" "$sysroot/lib/rustlib/$host/bin/rust-objcopy" "$@"; }

rm -rf "${dist:?}/include" "$dist/lib"
mkdir -p "$dist/include" "$dist/lib/cmake/aaglsd"
cp ffi/include/aaglsd.h "$dist/include/"

# One cargo invocation for all targets, so that they build in parallel.
# `cargo build` of the lib, not `cargo rustc --crate-type staticlib` (one
# target at a time): bare-metal targets get the staticlib alone, and rustc
# says so for each ("dropping unsupported crate type `cdylib`"), which is
# filtered out below. No build script of aaglsd-ffi, so no cbindgen here.
t0=$SECONDS
target_args=()
for t in $targets; do target_args+=(--target "$t"); done
log=$(mktemp)
rc=0
profile=${AAGLSD_DIST_PROFILE:-dist}
cargo build --quiet -p aaglsd-ffi --lib --profile "$profile" "${target_args[@]}" 2>"$log" || rc=$?
grep -v -e 'dropping unsupported crate type `cdylib`' "$log" | cat -s | sed '/^$/d' >&2 || true
rm -f "$log"
[ "$rc" -eq 0 ] || exit "$rc"
echo "  built in $((SECONDS - t0)) s"
for t in $targets; do
    mkdir -p "$dist/lib/$t"
    # The precompiled core and compiler_builtins keep their DWARF otherwise.
    objcopy --strip-debug "$target_dir/$t/$profile/libaaglsd.a" "$dist/lib/$t/libaaglsd.a"
    printf '  %-28s %9d bytes\n' "$t" "$(stat -c %s "$dist/lib/$t/libaaglsd.a")"
done

version=$(sed -n 's/^version = "\(.*\)"$/\1/p' ffi/Cargo.toml | head -n 1)
sed "s/@AAGLSD_VERSION@/$version/" ffi/dist/aaglsdConfig.cmake >"$dist/lib/cmake/aaglsd/aaglsdConfig.cmake"
sed "s/@AAGLSD_VERSION@/$version/" ffi/dist/aaglsdConfigVersion.cmake \
    >"$dist/lib/cmake/aaglsd/aaglsdConfigVersion.cmake"
sed "s/@AAGLSD_VERSION@/$version/" ffi/dist/README.md >"$dist/README.md"
cp LICENSE-MIT LICENSE-APACHE "$dist/"
{
    echo "Crates compiled into lib/*/libaaglsd.a (name version licence), besides Rust's"
    echo "core and compiler_builtins (MIT OR Apache-2.0):"
    echo
    # The same crates for every bare-metal target.
    cargo tree --quiet -p aaglsd-ffi --target "${targets%% *}" -e normal,no-proc-macro --prefix none \
        --format '{p} {l}' | sed 's/ (\/[^)]*)//' | sort -u
} >"$dist/THIRD-PARTY.txt"
echo "aaglsd $version distributable in $dist"
