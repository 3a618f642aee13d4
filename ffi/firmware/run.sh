#!/usr/bin/env bash
# The C firmware example (ffi/firmware/) under QEMU: mps2-an386 (Cortex-M4F,
# newlib-nano) or, with FW_BOARD=virt-rv32, the RISC-V virt machine (RV32IMAC,
# picolibc).
#
#   bash ffi/firmware/run.sh IMAGE.pgm            build, then run on IMAGE: the segments on
#                                                 stdout; the summary, stack high-water and
#                                                 instruction count on stderr
#   bash ffi/firmware/run.sh FRAME.yuyv W H       the same on a YUYV frame (luma in place)
#   bash ffi/firmware/run.sh --check              CI: ffi/tests/sizes.c on the board; every
#                                                 committed image and corpus pattern, as PGM
#                                                 and as YUYV, against the host CLI; then
#                                                 stack, instructions, flash
#
# Environment:
#   AAGLSD_DIST  the distributable to build against (default: a fresh
#                `ffi/dist.sh` of the boards' targets into target/ffi-firmware/dist)
#   FW_BOARD     mps2-an386 (default) or virt-rv32; --check also takes "all"
#   FW_BUILD     make (default) or cmake; --check also takes "both"
#   FW_CORPUS    corpus patterns for --check (default "hatch-a30 hatch-a60 stripes-a30-p3")
#   FW_TIMEOUT   seconds per QEMU run (default 300)
#   YORK_DIR     York Urban images (default <repo>/../shared/data/yorkurban); its crop
#                is checked too when there
#
# Installs, only when missing: gcc-arm-none-eabi and libnewlib-arm-none-eabi
# or gcc-riscv64-unknown-elf and picolibc-riscv64-unknown-elf, make, cmake (for
# the cmake build), qemu-system-arm or qemu-system-riscv (Debian 12 backports,
# as firmware/run.sh does). The C build runs with PATH=/usr/bin:/bin: no Rust.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
cd "$root"

# stdout carries the firmware's segments only; everything else to stderr.
exec 3>&1 1>&2

check=0
if [ "${1:-}" = --check ]; then
    check=1
    [ $# -eq 1 ] || { echo "usage: run.sh --check" >&2; exit 2; }
elif [ $# -ne 1 ] && [ $# -ne 3 ]; then
    echo "usage: run.sh IMAGE.pgm | run.sh FRAME.yuyv WIDTH HEIGHT | run.sh --check" >&2
    exit 2
fi
boards=${FW_BOARD:-mps2-an386}
[ "$boards" != all ] || boards="mps2-an386 virt-rv32"
[ "$check" -eq 1 ] || [ "$(wc -w <<<"$boards")" -eq 1 ] || { echo "FW_BOARD: one board to run an image" >&2; exit 2; }
# Per board: the archive, the C compiler, the CMake toolchain file, QEMU.
declare -A b_target=([mps2-an386]=thumbv7em-none-eabihf [virt-rv32]=riscv32imc-unknown-none-elf)
declare -A b_cc=([mps2-an386]=arm-none-eabi-gcc [virt-rv32]=riscv64-unknown-elf-gcc)
declare -A b_toolchain=([mps2-an386]=arm-none-eabi.cmake [virt-rv32]=riscv32.cmake)
declare -A b_qemu=(
    [mps2-an386]="qemu-system-arm -machine mps2-an386 -cpu cortex-m4"
    [virt-rv32]="qemu-system-riscv32 -machine virt -bios none"
)
for b in $boards; do
    [ -n "${b_target[$b]:-}" ] || { echo "FW_BOARD: mps2-an386, virt-rv32 or all, not '$b'" >&2; exit 2; }
done
builds=${FW_BUILD:-make}
[ "$builds" != both ] || builds="make cmake"
[ "$check" -eq 1 ] || [ "$(wc -w <<<"$builds")" -eq 1 ] || { echo "FW_BUILD: one build to run an image" >&2; exit 2; }
for b in $builds; do
    case $b in
    make | cmake) ;;
    *)
        echo "FW_BUILD: make, cmake or both (--check), not '$b'" >&2
        exit 2
        ;;
    esac
done
timeout_s=${FW_TIMEOUT:-300}
target_dir=$(cargo metadata --format-version 1 --no-deps 2>/dev/null |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
work=${target_dir:-$root/target}/ffi-firmware
mkdir -p "$work"
t_start=$SECONDS

# --- tools ---------------------------------------------------------------------
apt_get() {
    DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 "$@"
}
missing=()
qemu_pkgs=()
case " $boards " in *" mps2-an386 "*)
    command -v arm-none-eabi-gcc >/dev/null || missing+=(gcc-arm-none-eabi)
    [ -f /usr/lib/arm-none-eabi/lib/nano.specs ] || missing+=(libnewlib-arm-none-eabi)
    command -v arm-none-eabi-size >/dev/null || missing+=(binutils-arm-none-eabi)
    command -v qemu-system-arm >/dev/null || qemu_pkgs+=(qemu-system-arm)
    ;;
esac
case " $boards " in *" virt-rv32 "*)
    command -v riscv64-unknown-elf-gcc >/dev/null || missing+=(gcc-riscv64-unknown-elf)
    [ -d /usr/lib/picolibc/riscv64-unknown-elf ] || missing+=(picolibc-riscv64-unknown-elf)
    command -v qemu-system-riscv32 >/dev/null || qemu_pkgs+=(qemu-system-riscv)
    ;;
esac
command -v make >/dev/null || missing+=(make)
case " $builds " in *" cmake "*) command -v cmake >/dev/null || missing+=(cmake) ;; esac
if [ ${#missing[@]} -gt 0 ]; then
    echo "== apt-get install ${missing[*]}"
    apt_get update -qq
    apt_get install -y -qq --no-install-recommends "${missing[@]}"
fi
if [ ${#qemu_pkgs[@]} -gt 0 ]; then
    # Debian 12's QEMU 7.2 would remove the image's qemu-utils 10.0; the
    # backports QEMU matches it (firmware/run.sh does the same).
    src=/etc/apt/sources.list.d/debian.sources
    bpo=/etc/apt/sources.list.d/bookworm-backports.sources
    if [ -f "$src" ] && grep -q '^Suites:.*bookworm' "$src"; then
        [ -f "$bpo" ] || awk 'BEGIN{RS="";ORS="\n\n"} NR==1' "$src" |
            sed -e 's/^Suites:.*/Suites: bookworm-backports/' -e '/^#/d' >"$bpo"
        apt_get update -qq
        apt_get install -y -qq --no-install-recommends -t bookworm-backports "${qemu_pkgs[@]}"
    else
        apt_get update -qq
        apt_get install -y -qq --no-install-recommends "${qemu_pkgs[@]}"
    fi
fi

# --- distributable and build ---------------------------------------------------
if [ -n "${AAGLSD_DIST:-}" ]; then
    dist=$(cd "$AAGLSD_DIST" && pwd)
else
    dist=$work/dist
    echo "== ffi/dist.sh $dist"
    targets=""
    for b in $boards; do targets="$targets ${b_target[$b]}"; done
    AAGLSD_DIST_TARGETS=${AAGLSD_DIST_TARGETS:-${targets# }} bash ffi/dist.sh "$dist"
fi
# The C side needs no Rust: the builds see only the system's tools.
c_env=(env -i PATH=/usr/bin:/bin HOME="$HOME")
declare -A elf # keyed "BOARD BUILD"
for board in $boards; do
    for b in $builds; do
        echo "== build ($board, $b, against $dist)"
        dir=$work/$board-$b
        case $b in
        make)
            "${c_env[@]}" make -s -C "$here" AAGLSD_DIST="$dist" BOARD="$board" BUILD="$dir"
            ;;
        cmake)
            # A cache from another distributable would keep its aaglsd_DIR.
            rm -f "$dir/CMakeCache.txt"
            "${c_env[@]}" cmake -S "$here" -B "$dir" -DCMAKE_TOOLCHAIN_FILE="$here/${b_toolchain[$board]}" \
                -DCMAKE_PREFIX_PATH="$dist" >"$dir.log" || { cat "$dir.log"; exit 1; }
            grep 'aaglsd' "$dir.log" || true
            "${c_env[@]}" cmake --build "$dir" >>"$dir.log" || { cat "$dir.log"; exit 1; }
            ;;
        esac
        elf["$board $b"]=$dir/fw.elf
    done
done

# QEMU for board $1 with the firmware ELF $2 and the firmware's arguments
# after them.
qemu() {
    local board=$1 e=$2 args=arg=fw
    shift 2
    for a in "$@"; do args="$args,arg=$a"; done
    # shellcheck disable=SC2086 # b_qemu holds several arguments
    timeout "$timeout_s" ${b_qemu[$board]} -nographic \
        -semihosting-config "enable=on,target=native,$args" -icount shift=0 -kernel "$e" </dev/null
}

if [ "$check" -eq 0 ]; then
    rc=0
    qemu "$boards" "${elf["$boards $builds"]}" "$@" >&3 || rc=$?
    [ "$rc" -eq 0 ] || echo "firmware/QEMU exit status $rc" >&2
    exit "$rc"
fi

# --- check: the formatter, then every image against the host CLI ---------------
echo "== f32_text against Rust's {} (every 9973rd bit pattern, 2^20 from 1.0, specials)"
cc -std=c11 -O2 -Wall -Wextra -Werror -I"$here" "$here/test/f32_text_check.c" "$here/f32_text.c" \
    -o "$work/f32_text_check"
rustc -O --edition 2021 "$here/test/f32_text_check.rs" -o "$work/f32_text_check_rs"
"$work/f32_text_check" 9973 0x3f800000 1048576 >"$work/f32_c.txt"
"$work/f32_text_check_rs" 9973 0x3f800000 1048576 >"$work/f32_rs.txt"
cmp "$work/f32_c.txt" "$work/f32_rs.txt" || {
    diff "$work/f32_c.txt" "$work/f32_rs.txt" | head
    echo "FAIL: f32_text differs from Rust's text"
    exit 1
}
echo "  $(wc -l <"$work/f32_c.txt") values: identical"

echo "== ffi/tests/sizes.c on each board (32-bit size_t): the compile-time sizes vs the functions"
for board in $boards; do
    "${c_env[@]}" make -s -C "$here" AAGLSD_DIST="$dist" BOARD="$board" BUILD="$work/$board-sizes" sizes
    qemu "$board" "$work/$board-sizes/sizes.elf" >"$work/$board-sizes.txt" 2>&1 || {
        cat "$work/$board-sizes.txt"
        echo "FAIL: the compile-time sizes differ from the functions on $board"
        exit 1
    }
    echo "  $board: $(grep 'sizes checked' "$work/$board-sizes.txt")"
done

echo "== inputs (PGM and YUYV) and the host CLI's output on each"
inputs=(testdata/castle1_320x240.gray testdata/castle1.png testdata/castle1_crop.jpg)
york=${YORK_DIR:-$root/../shared/data/yorkurban}/P1080078.jpg
if [ -f "$york" ]; then
    inputs+=("crop:$york:200:100")
else
    echo "  (no $york: the York crop is left out)"
fi
for p in ${FW_CORPUS-hatch-a30 hatch-a60 stripes-a30-p3}; do inputs+=("corpus:$p"); done
cargo build --quiet --release --example detect
cargo run --quiet -p aaglsd-ffi --release --example fw_inputs -- "$work/img" "${inputs[@]}" \
    >"$work/inputs.txt"
host_cli=${target_dir:-$root/target}/release/examples/detect
while read -r name w h; do
    "$host_cli" "$work/img/$name.pgm" --stats --scores >"$work/img/$name.host.txt" 2>"$work/img/$name.host.err"
done <"$work/inputs.txt"

ok=1
rows=()
for key in "${!elf[@]}"; do
    read -r board b <<<"$key"
    while read -r name w h; do
        for mode in pgm yuyv; do
            out=$work/img/$name.$board-$b.$mode
            if [ "$mode" = pgm ]; then set -- "$work/img/$name.pgm"; else set -- "$work/img/$name.yuyv" "$w" "$h"; fi
            rc=0
            qemu "$board" "${elf[$key]}" "$@" >"$out.txt" 2>"$out.err" || rc=$?
            if [ "$rc" -ne 0 ]; then
                echo "FAIL: $name ($board, $b, $mode): exit status $rc"
                cat "$out.err"
                ok=0
                continue
            fi
            # The segments, and stderr but the firmware's own "fw:" lines
            # (summary, warning, count), as the host CLI's with --stats.
            if ! cmp -s "$out.txt" "$work/img/$name.host.txt" ||
                ! cmp -s <(grep -v '^fw: ' "$out.err") "$work/img/$name.host.err"; then
                echo "FAIL: $name ($board, $b, $mode) differs from the host CLI:"
                diff "$work/img/$name.host.txt" "$out.txt" | head -n 5 || true
                diff "$work/img/$name.host.err" <(grep -v '^fw: ' "$out.err") || true
                ok=0
                continue
            fi
            segs=$(wc -l <"$out.txt")
            stack=$(sed -n 's/^fw: stack high-water of the detection: \([0-9]*\) bytes$/\1/p' "$out.err")
            insns=$(sed -n 's/^fw: instructions in the detection: \([0-9]*\) .*/\1/p' "$out.err")
            rows+=("$(printf '%-10s %-5s %-22s %-4s %4sx%-4s %5s %11s %8.1f %6s' "$board" "$b" "$name" "$mode" \
                "$w" "$h" "$segs" "$insns" "$(awk -v n="$insns" -v p="$((w * h))" 'BEGIN{print n/p}')" "$stack")")
        done
    done <"$work/inputs.txt"
done
echo "== the example under QEMU -icount shift=0 (instructions of the aaglsd_detect call, not cycles)"
printf '  %-10s %-5s %-22s %-4s %9s %5s %11s %8s %6s\n' board build image mode size segs insns insns/px stack
printf '  %s\n' "${rows[@]}" | sort

# Flash: the allocated sections with contents (code, constants, the initial
# values of .data); static RAM: the writable allocated ones (.data, .bss),
# less picolibc's stack reservation. The stack and newlib's heap come on top.
sizes() { # ELF -> "flash ram flash_section_names"
    readelf -SW "$1" | awk '
        /^ *\[ *[0-9]+\]/ {
            sub(/^ *\[ *[0-9]+\] */, "")
            name = $1; type = $2; size = strtonum_hex($5); flags = $7
            if (flags !~ /A/ || name == ".stack" || name == ".heap") next
            if (type != "NOBITS") { flash += size; names = names " " name }
            if (flags ~ /W/) ram += size
        }
        function strtonum_hex(s,   i, n) {
            n = 0
            for (i = 1; i <= length(s); i++) n = n * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1
            return n
        }
        END { print flash + 0, ram + 0, names }'
}
# The bytes of the archive's input sections in those output sections, from
# the link map: libaaglsd.a's share of the flash.
lib_flash() { # MAP "SECTION..."
    awk -v list=" $2 " 'function hex(s,   i, n) {
             n = 0
             for (i = 3; i <= length(s); i++) n = n * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1
             return n
         }
         /^\.[A-Za-z_]/ {sec = $1}
         index(list, " " sec " ") && /libaaglsd\.a\(/ {
             for (i = 1; i <= NF; i++) if ($i ~ /^0x/ && $(i + 1) ~ /^0x/) { n += hex($(i + 1)); break }
         }
         END {print n + 0}' "$1"
}
links=()
for key in "${!elf[@]}"; do links+=("$key|${elf[$key]}"); done
case " $boards " in *" mps2-an386 "*)
    "${c_env[@]}" make -s -C "$here" AAGLSD_DIST="$dist" BUILD="$work/mps2-an386-make-nogc" GC=0
    links+=("mps2-an386 make, no --gc-sections|$work/mps2-an386-make-nogc/fw.elf")
    ;;
esac
echo "== flash and static RAM (readelf -S: flash = allocated sections with contents)"
printf '  %-36s %8s %10s %10s\n' link flash libaaglsd static_RAM
for l in "${links[@]}"; do
    read -r flash ram names < <(sizes "${l#*|}")
    printf '  %-36s %8d %10d %10d\n' "${l%%|*}" "$flash" "$(lib_flash "$(dirname "${l#*|}")/fw.map" "$names")" "$ram"
done | sort
if [ "$ok" -ne 1 ]; then
    echo "== FAIL: the C firmware's output differs from the host CLI's ($((SECONDS - t_start)) s)"
    exit 1
fi
n=$(wc -l <"$work/inputs.txt")
echo "== OK: the C firmware equals the host CLI on $n images x 2 inputs (PGM, YUYV) x $(wc -w <<<"$boards") boards ($boards) x $(wc -w <<<"$builds") builds ($builds), $((SECONDS - t_start)) s"
