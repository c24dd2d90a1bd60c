#!/usr/bin/env bash
# Flash and stack footprint of each library capability linked alone (examples/fw_footprint.rs),
# on Cortex-M0 and Cortex-M4F:
#   bash benches/footprint.sh            # measure, print the BENCHMARKS.md table
#   bash benches/footprint.sh --check    # ... and fail if a row grew past its snapshot's margin
#   bash benches/footprint.sh --update   # ... and rewrite the snapshot (benches/footprint.snapshot)
#
# For each capability: the size image (no formatting, no semihosting) is built and its
# `.text + .rodata` read with llvm-size; the capability's flash is that minus the same of the
# `baseline` image (runtime, `main` and idle loop only). The stack image runs under QEMU and
# prints the capability's stack high-water mark for each case of operands: the table shows the
# typical case and the worst. A further board is one more entry in `targets`/`labels`,
# a further capability one more name in `caps` (and in the example).
#
# Margin: --check fails when a row's flash, typical stack or worst-case stack exceeds its
# snapshot by more than 5 % + 32 bytes. Smaller than the snapshot by as much only prints a note.
# The toolchain is pinned (rust-toolchain.toml) and Cargo.lock fixed, so the numbers move only
# when code does.
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-}"
case "$mode" in "" | --check | --update) ;; *) echo "usage: $0 [--check|--update]" >&2; exit 2 ;; esac

targets=(thumbv6m-none-eabi thumbv7em-none-eabihf)
labels=(M0 M4F)
caps=(baseline gyro2 gyro2_q30 euler gyro2_euler strang exact all estimate estimate_light)
snapshot=benches/footprint.snapshot
target_dir="${CARGO_TARGET_DIR:-target}"
dir="$target_dir/footprint"
mkdir -p "$dir"
size_tool="$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin/llvm-size"
[ -x "$size_tool" ] || { echo "llvm-size not found: rustup component add llvm-tools" >&2; exit 1; }

# section NAME FILE: size in bytes of section NAME (0 if absent) in an `llvm-size -A` listing.
section() { awk -v s="$1" '$1==s {print $2; found=1} END {if (!found) print 0}' "$2"; }

current="$dir/current.txt"
: > "$current"
for t in "${targets[@]}"; do
  for c in "${caps[@]}"; do
    GYROSTAT_FOOTPRINT="$c" cargo build -q --profile firmware --example fw_footprint --target "$t"
    "$size_tool" -A "$target_dir/$t/firmware/examples/fw_footprint" > "$dir/$t-$c.size"
    GYROSTAT_FOOTPRINT="$c" GYROSTAT_FOOTPRINT_STACK=1 \
      cargo run -q --profile firmware --example fw_footprint --target "$t" > "$dir/$t-$c.stack"
    # Stack of the typical case (the first) and the worst over all cases.
    stack=$(awk -v c="$c" '$1=="footprint" && $2==c && $3=="stack" && NF>3 {
      w=$4; for (i=5;i<=NF;i++) if ($i>w) w=$i; print $4, w}' "$dir/$t-$c.stack")
    [ -n "$stack" ] || { echo "$t $c: no stack line in $dir/$t-$c.stack" >&2; exit 1; }
    f="$dir/$t-$c.size"
    code=$(( $(section .text "$f") + $(section .rodata "$f") ))
    image=$(( $(section .vector_table "$f") + code + $(section .data "$f") ))
    echo "$t $c $code $image $stack" >> "$current"
  done
done

# Library share: code minus the baseline image's code (the baseline row keeps its own).
rows=$(awk '
  $2=="baseline" {base[$1]=$3}
  {code[NR]=$3; t[NR]=$1; c[NR]=$2; img[NR]=$4; st[NR]=$5; sw[NR]=$6}
  END {for (i=1;i<=NR;i++) print t[i], c[i], (c[i]=="baseline" ? code[i] : code[i]-base[t[i]]), img[i], st[i], sw[i]}
' "$current")

describe() {
  case "$1" in
    baseline) echo "runtime alone: cortex-m-rt reset, \`main\`, idle loop" ;;
    gyro2) echo "2-sample gyro update + fast renormalisation, \`coning2_update\`" ;;
    gyro2_q30) echo "\`gyro2\` in Q1.30 fixed point (integer only), \`coning2_update\` on \`UnitQuat<Q30>\`" ;;
    euler) echo "quaternion → Euler ZYX with gimbal-lock record, \`to_euler(ZYX, ZeroThird)\`" ;;
    strang) echo "rigid body from principal moments + one Strang step" ;;
    exact) echo "exact free rigid body from principal moments, \`FreeRigidBody::try_new\` + \`try_state_at\`" ;;
    gyro2_euler) echo "\`gyro2\` and \`euler\` together" ;;
    all) echo "the four f32 capabilities together" ;;
    estimate) echo "attitude estimator, default parameters: \`Estimator::try_new\` + two \`update_9d\`" ;;
    estimate_light) echo "attitude estimator, light mode (\`Mode::Light\`, fixed at build time): \`Estimator::try_new\` + two \`update_9d\`" ;;
  esac
}
value() { echo "$rows" | awk -v t="$1" -v c="$2" -v k="$3" '$1==t && $2==c {print $k}'; }

header="| capability (f32 unless named)"; rule="|---"
for l in "${labels[@]}"; do
  header="$header | $l flash | $l image | $l stack"; rule="$rule|---:|---:|---:"
done
echo "$header |"; echo "$rule|"
for c in "${caps[@]}"; do
  row="| \`$c\`: $(describe "$c")"
  for t in "${targets[@]}"; do
    row="$row | $(value "$t" "$c" 3) | $(value "$t" "$c" 4) | $(value "$t" "$c" 5) / $(value "$t" "$c" 6)"
  done
  echo "$row |"
done

if [ "$mode" = --update ]; then
  {
    echo "# Footprint snapshot checked by \`bash benches/footprint.sh --check\` (CI); rewrite with"
    echo "# \`bash benches/footprint.sh --update\`. Columns: target, capability, flash bytes (.text +"
    echo "# .rodata; for capabilities, the image minus the baseline image), stack bytes of the"
    echo "# typical case, stack bytes of the worst case."
    echo "$rows" | awk '{print $1, $2, $3, $5, $6}'
  } > "$snapshot"
  echo "-- wrote $snapshot"
elif [ "$mode" = --check ]; then
  [ -f "$snapshot" ] || { echo "no $snapshot: run with --update" >&2; exit 1; }
  fail=0
  while read -r t c flash stack worst; do
    case "$t" in "#"* | "") continue ;; esac
    if [ -z "$(value "$t" "$c" 3)" ]; then echo "FAIL $t $c: in the snapshot but not measured"; fail=1; continue; fi
    for kind in flash stack worst; do
      case "$kind" in
        flash) old=$flash; new=$(value "$t" "$c" 3) ;;
        stack) old=$stack; new=$(value "$t" "$c" 5) ;;
        worst) old=$worst; new=$(value "$t" "$c" 6) ;;
      esac
      limit=$(( old + old * 5 / 100 + 32 ))
      if [ "$new" -gt "$limit" ]; then
        echo "FAIL $t $c $kind: $new bytes, snapshot $old (limit $limit = +5 % + 32 B)"; fail=1
      elif [ "$new" -lt $(( old - old * 5 / 100 - 32 )) ]; then
        echo "note $t $c $kind: $new bytes, snapshot $old: smaller; refresh with --update"
      fi
    done
  done < "$snapshot"
  while read -r t c _; do
    if ! grep -q "^$t $c " "$snapshot"; then echo "FAIL $t $c: measured but not in the snapshot"; fail=1; fi
  done <<< "$rows"
  if [ "$fail" -ne 0 ]; then
    echo "footprint grew past the margin: find the cause, or if the growth is intended," \
      "rewrite the snapshot with 'bash benches/footprint.sh --update' and the table in BENCHMARKS.md" >&2
    exit 1
  fi
  echo "-- footprint within 5 % + 32 B of $snapshot for every row"
fi
