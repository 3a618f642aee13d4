#!/usr/bin/env bash
# Per-function instruction profile of the firmware under QEMU (not for CI:
# about 3 minutes and 65 M log lines for one 320x240 image).
#
#   [FW_CPU=m4|m33|m0] firmware/profile.sh [IMAGE.gray] [PROFILE]
#
# Defaults: the Cortex-M4, testdata/castle1_320x240.gray, profile release
# (FW_CPU as in run.sh, one CPU). QEMU logs every
# executed instruction (one instruction per block, -d exec,nochain) into a
# FIFO; awk counts them per PC; addr2line maps each PC to its inline chain.
# Prints the instructions per pixel of each pipeline function (the outermost
# aaglsd function of the chain below `detect`), of each innermost function,
# and of each source line. Needs run.sh's tools (qemu-system-arm,
# binutils-arm-none-eabi for arm-none-eabi-addr2line).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
image="$(realpath "${1:-$here/../testdata/castle1_320x240.gray}")"
prof="${2:-release}"
pixels=76800
cd "$here"

# As in run.sh: build target and QEMU machine per CPU.
case "${FW_CPU:-m4}" in
    m4) target=thumbv7em-none-eabihf machine="-machine mps2-an386 -cpu cortex-m4" ;;
    m33) target=thumbv8m.main-none-eabihf machine="-machine mps2-an505 -cpu cortex-m33" ;;
    m0) target=thumbv6m-none-eabi machine="-machine microbit -global nrf51-soc.sram-size=0x80000" ;;
    *) echo "FW_CPU: unknown CPU '$FW_CPU' (m4, m33 or m0)" >&2 && exit 2 ;;
esac

cargo build --profile "$prof" --target "$target" --quiet --bin firmware
work="target/profile"
mkdir -p "$work"
# A private copy: a concurrent build must not swap the ELF under addr2line.
elf="$work/firmware.elf"
cp "target/$target/$prof/firmware" "$elf"
rm -f "$work/fifo"
mkfifo "$work/fifo"

# Log lines: "Trace 0: 0x... [flags/PC/flags/flags] symbol"; field 3 is the PC.
awk -F'[][/]' 'NF > 3 && $3 ~ /^[0-9a-f]+$/ {c[$3]++} END {for (k in c) print c[k], k}' \
    "$work/fifo" >"$work/pc_counts.txt" &
agg=$!
# One instruction per translation block: QEMU 8 names it a TCG property,
# QEMU 7 (Debian 12's) has the older -singlestep flag.
qemu_major=$(qemu-system-arm --version | sed -n 's/^QEMU emulator version \([0-9]*\).*/\1/p')
if [ "${qemu_major:-0}" -ge 8 ]; then
    one_insn="-accel tcg,one-insn-per-tb=on"
else
    one_insn="-singlestep"
fi
# shellcheck disable=SC2086 # $machine and $one_insn hold several arguments
timeout 900 qemu-system-arm $machine -nographic \
    -semihosting-config "enable=on,target=native,arg=firmware,arg=$image" \
    -icount shift=0 $one_insn -d exec,nochain -D "$work/fifo" \
    -kernel "$elf" </dev/null >"$work/firmware.txt"
wait "$agg"
rm -f "$work/fifo"
grep '^# detect:' "$work/firmware.txt"

awk '{print "0x" $2}' "$work/pc_counts.txt" |
    arm-none-eabi-addr2line -a -f -i -C -e "$elf" >"$work/addr2line.txt"

# Block k of addr2line's output (an address line, then function/location
# pairs, innermost first) belongs to line k of pc_counts.txt.
awk -v px="$pixels" -v out="$work" '
function clean(f) { sub(/::h[0-9a-f]+$/, "", f); return f }
function flush(   i, st, c) {
    if (k == 0 || m == 0) return
    c = cnt[k]
    inner[clean(fn[1])] += c
    split(loc[1], l, " ")
    sub(/^.*\/(src|library)\//, "", l[1])
    line[l[1]] += c
    st = ""
    for (i = m; i >= 1; i--) {
        if (fn[i] ~ /^aaglsd::/) {
            if (st ~ /^aaglsd::detect::detect(_with)?$/) { st = "detect > " clean(fn[i]); break }
            if (st == "") st = clean(fn[i])
        }
    }
    if (st == "") st = clean(fn[m])
    stage[st] += c
}
NR == FNR { cnt[FNR] = $1; next }
/^0x/ { flush(); k++; m = 0; odd = 0; next }
{ if (odd = !odd) fn[++m] = $0; else loc[m] = $0 }
END {
    flush()
    for (s in stage) printf "%8.1f  %s\n", stage[s] / px, s > (out "/by_stage.txt")
    for (s in inner) printf "%8.1f  %s\n", inner[s] / px, s > (out "/by_function.txt")
    for (s in line) printf "%8.1f  %s\n", line[s] / px, s > (out "/by_line.txt")
}' "$work/pc_counts.txt" "$work/addr2line.txt"

for t in stage function line; do
    echo "== instructions per pixel by $t (top 25; all in firmware/$work/by_$t.txt)"
    sort -rn "$work/by_$t.txt" -o "$work/by_$t.txt"
    head -n 25 "$work/by_$t.txt"
done
