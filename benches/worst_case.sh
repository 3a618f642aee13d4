#!/usr/bin/env bash
# Worst case in instructions per pixel (issue #16): the detector on the
# adversarial corpus (aaglsd_support::corpus) against York Urban.
#
#   bash benches/worst_case.sh [--quick] [--jobs N] [--size WxH]
#        [--profiles "default official paper"] [--timeout S] [--keep]
#
# For every profile, counts with valgrind's callgrind the instructions of
# the detection alone (`aaglsd::detect::detect_with`, the body of
# `aaglsd::detect`: no decoding, allocation or output) in one run of the
# CLI (`target/release/examples/detect IMAGE --profile P --json`) per image,
# divides by the pixel count, and prints markdown tables: per profile, the
# York median and maximum, the worst corpus pattern and its ratio to the
# York median, then the five worst patterns.
#
# Instruction counts are exact and repeatable (unlike times on a shared
# machine), so the ratio is a property of the code, not of the load.
#
# Images: all 51 York Urban images (`--quick`: every sixth, 9) from
# $AAGLSD_SHARED/data/yorkurban (default ../shared beside the repository),
# and the corpus written by `worst_case --write` (640x480 unless --size).
# Runs --jobs (default 2) callgrinds at a time; each takes 1-3 s for a
# York image, a run over --timeout seconds (default 600) is reported as
# a timeout. Full: 3 x 90 runs, about 8.5 minutes on 2 cores; --quick:
# 3 x 48, about 5 (the corpus dominates, and `paper` is the slowest;
# `default` is `official` today, so --profiles "default paper" saves a third).
# Results: target/worst_case/results.tsv (profile, set, image, Ir, pixels);
# --keep also keeps the callgrind files there (for callgrind_annotate).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
quick=0 jobs=2 size=640x480 timeout=600 keep=0
profiles="default official paper"
while [ $# -gt 0 ]; do
    case $1 in
        --quick) quick=1 ;;
        --jobs) jobs=$2; shift ;;
        --size) size=$2; shift ;;
        --profiles) profiles=$2; shift ;;
        --timeout) timeout=$2; shift ;;
        --keep) keep=1 ;;
        -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
        *) echo "worst_case.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
    esac
    shift
done
for tool in valgrind awk xargs timeout cargo; do
    command -v "$tool" >/dev/null || { echo "worst_case.sh: needs $tool" >&2; exit 1; }
done

york=${AAGLSD_SHARED:-$root/../shared}/data/yorkurban
out=$root/target/worst_case
rm -rf "$out"
mkdir -p "$out/cg"

(cd "$root" && cargo build --quiet --release --example detect --example worst_case)
bin=$root/target/release/examples
"$bin/worst_case" --write "$out/corpus" --size "$size"

# One job a line: profile, set (york or corpus), image path.
{
    for p in $profiles; do
        if [ -d "$york" ]; then
            find "$york" -maxdepth 1 -name '*.jpg' | sort |
                awk -v q="$quick" -v p="$p" '!q || NR % 6 == 1 { print p, "york", $0 }'
        fi
        find "$out/corpus" -name '*.pgm' | sort | awk -v p="$p" '{ print p, "corpus", $0 }'
    done
} >"$out/jobs"
[ -d "$york" ] || echo "worst_case.sh: no $york: corpus only" >&2
echo "$(wc -l <"$out/jobs") callgrind runs, $jobs at a time..." >&2

# One run: prints `profile set stem Ir pixels` (Ir "timeout" or "failed").
measure() {
    local profile=$1 set=$2 img=$3 stem base
    stem=$(basename "$img"); stem=${stem%.*}
    base=$out/cg/$profile.$set.$stem
    if timeout "$timeout" valgrind --tool=callgrind \
        --toggle-collect='aaglsd::detect::detect_with*' \
        --callgrind-out-file="$base.cg" \
        "$bin/detect" "$img" --profile "$profile" --json >"$base.json" 2>"$base.log"; then
        local ir px
        ir=$(awk '/^totals:/ { t = $2 } /^summary:/ { s = $2 } END { print t ? t : s }' "$base.cg")
        px=$(head -c 64 "$base.json" | sed -E 's/^\{"width":([0-9]+),"height":([0-9]+).*/\1 * \2/')
        [ "${ir:-0}" -gt 0 ] || ir=failed # detect_with was not found: no count
        echo "$profile $set $stem $ir $((px))"
    else
        [ $? -eq 124 ] && echo "$profile $set $stem timeout 0" || echo "$profile $set $stem failed 0"
    fi
    [ "$keep" = 1 ] || rm -f "$base.cg" "$base.json"
}
export -f measure
export out bin timeout keep
xargs -P "$jobs" -L 1 bash -c 'measure "$@"' _ <"$out/jobs" | sort >"$out/results.tsv"

if grep -qE ' (timeout|failed) ' "$out/results.tsv"; then
    echo "worst_case.sh: runs without a count (logs in $out/cg):" >&2
    grep -E ' (timeout|failed) ' "$out/results.tsv" >&2
fi

# The tables. Per profile: York instr/px sorted for the median, corpus
# sorted worst first.
echo
echo "Instructions per pixel in \`aaglsd::detect\` (callgrind), corpus at $size, $(
    [ "$quick" = 1 ] && echo "9 York Urban images (--quick)" || echo "all York Urban images")."
echo
echo "| profile | York median instr/px | York max | worst pattern | its instr/px | ratio |"
echo "|---|---|---|---|---|---|"
top=""
for p in $profiles; do
    ymed=$(awk -v p="$p" '$1 == p && $2 == "york" && $4 ~ /^[0-9]+$/ { print $4 / $5 }' "$out/results.tsv" |
        sort -g | awk '{ v[NR] = $1 } END { if (NR) print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2); else print 0 }')
    ymax=$(awk -v p="$p" '$1 == p && $2 == "york" && $4 ~ /^[0-9]+$/ { print $4 / $5 }' "$out/results.tsv" |
        sort -g | tail -n 1)
    awk -v p="$p" '$1 == p && $2 == "corpus" && $4 ~ /^[0-9]+$/ { print $4 / $5, $3 }' "$out/results.tsv" |
        sort -gr >"$out/corpus.$p"
    read -r worst_v worst_n <"$out/corpus.$p" || { worst_v=0 worst_n=-; }
    awk -v p="$p" -v m="$ymed" -v x="${ymax:-0}" -v v="$worst_v" -v n="$worst_n" 'BEGIN {
        printf "| %s | %.0f | %.0f | %s | %.0f | %s |\n", p, m, x, n, v, (m > 0 ? sprintf("%.1f", v / m) : "-") }'
    top+=$(awk -v p="$p" -v m="$ymed" 'NR <= 5 { c = c sprintf(" %s %.0f (%s) |", $2, $1, (m > 0 ? sprintf("%.1fx", $1 / m) : "-")) }
        END { printf "| %s |%s\n", p, c }' "$out/corpus.$p")$'\n'
done
echo
echo "Five worst patterns: instr/px (ratio to the York median)."
echo
echo "| profile | 1 | 2 | 3 | 4 | 5 |"
echo "|---|---|---|---|---|---|"
printf '%s' "$top"
