#!/usr/bin/env bash
# Checks a distributable (`ffi/dist.sh DIR`) the way a C team uses it: a
# cross compiler and CMake, no Rust (PATH=/usr/bin:/bin). For each core and
# float ABI below, find_package(aaglsd) must pick the expected archive (or
# none), and ffi/dist/test/link.c, which calls every aaglsd_ function and
# sizes its buffers with the compile-time macros, must compile with -Wall
# -Wextra -Werror and link against it (newlib's nosys stubs; picolibc on
# RISC-V, with picolibc's default memory layout). The RISC-V rows need riscv64-unknown-elf-gcc and picolibc, and
# are skipped (said so) without them.
#
#   bash ffi/dist/check.sh DIR
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
[ $# -eq 1 ] || {
    echo "usage: bash ffi/dist/check.sh DIR" >&2
    exit 2
}
dist="$(cd "$1" && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# compiler | flags | expected archive ("none": find_package must refuse)
arm=arm-none-eabi-gcc
rv=riscv64-unknown-elf-gcc
cases=(
    "$arm|-mcpu=cortex-m0plus -mthumb|thumbv6m-none-eabi"
    "$arm|-mcpu=cortex-m3 -mthumb|thumbv6m-none-eabi"
    "$arm|-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16|thumbv7em-none-eabihf"
    "$arm|-mcpu=cortex-m4 -mthumb -mfloat-abi=softfp -mfpu=fpv4-sp-d16|thumbv7em-none-eabi"
    "$arm|-mcpu=cortex-m4 -mthumb -mfloat-abi=soft|thumbv7em-none-eabi"
    "$arm|-mcpu=cortex-m7 -mthumb -mfloat-abi=hard -mfpu=fpv5-d16|thumbv7em-none-eabihf"
    "$arm|-mcpu=cortex-m23 -mthumb|thumbv6m-none-eabi"
    "$arm|-mcpu=cortex-m33 -mthumb -mfloat-abi=hard -mfpu=fpv5-sp-d16|thumbv8m.main-none-eabihf"
    "$arm|-mcpu=cortex-m33 -mthumb -mfloat-abi=soft|thumbv7em-none-eabi"
    "$arm|-mcpu=cortex-m33+nodsp -mthumb -mfloat-abi=soft|thumbv6m-none-eabi"
    "$arm|-mcpu=cortex-m55 -mthumb -mfloat-abi=hard|thumbv8m.main-none-eabihf"
    # Debian's picolibc has an rv32imac multilib, none for rv32imc.
    "$rv|-march=rv32imac -mabi=ilp32 --specs=picolibc.specs|riscv32imc-unknown-none-elf"
    "$rv|-march=rv32imafc -mabi=ilp32f --specs=picolibc.specs|none"
    "$rv|-march=rv32im -mabi=ilp32 --specs=picolibc.specs|none"
)
fail=0
n=0
printf '  %-80s %-28s %s\n' "compiler and flags" "archive picked" "link"
for c in "${cases[@]}"; do
    IFS='|' read -r cc flags want <<<"$c"
    if ! command -v "$cc" >/dev/null; then
        printf '  %-80s SKIPPED: no %s\n' "$cc $flags" "$cc"
        continue
    fi
    link_opts=""
    [ "$cc" != "$arm" ] || link_opts="--specs=nosys.specs"
    b=$work/$n
    n=$((n + 1))
    log=$b.log
    rc=0
    env -i PATH=/usr/bin:/bin HOME="$HOME" cmake -S "$here/test" -B "$b" \
        -DCMAKE_SYSTEM_NAME=Generic -DCMAKE_C_COMPILER="$cc" -DCMAKE_C_FLAGS="$flags" \
        -DCMAKE_TRY_COMPILE_TARGET_TYPE=STATIC_LIBRARY -DCMAKE_BUILD_TYPE=MinSizeRel \
        -DCMAKE_PREFIX_PATH="$dist" -DAAGLSD_CHECK_LINK_OPTIONS="$link_opts" >"$log" 2>&1 || rc=$?
    got=$(cat "$b/rust_target.txt" 2>/dev/null || echo "cmake failed")
    linked="-"
    if [ "$rc" -eq 0 ] && [ "$got" != none ]; then
        if env -i PATH=/usr/bin:/bin HOME="$HOME" cmake --build "$b" >>"$log" 2>&1; then
            linked=ok
        else
            linked=FAILED
        fi
    fi
    verdict=""
    if [ "$got" != "$want" ] || [ "$linked" = FAILED ]; then
        verdict="  <- FAIL (want $want)"
        fail=1
        sed 's/^/      /' "$log" | tail -n 20
    fi
    printf '  %-80s %-28s %s%s\n' "$cc $flags" "$got" "$linked" "$verdict"
done
if [ "$fail" -ne 0 ]; then
    echo "FAIL: the distributable's CMake package picked a wrong archive or did not link"
    exit 1
fi
echo "ok: $n configurations picked their archive and linked (or were refused) as expected"
