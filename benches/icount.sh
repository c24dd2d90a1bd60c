#!/usr/bin/env bash
# Regenerates the QEMU instruction-count table of BENCHMARKS.md:
#   bash benches/icount.sh
# Runs examples/fw_icount.rs and examples/fw_icount_estimation.rs under QEMU (-icount, deterministic) on Cortex-M4F (mps2-an386,
# hard float), Cortex-M33 (mps2-an505, hard float), Cortex-M3 (lm3s6965evb, soft float) and
# Cortex-M0 (microbit, soft float), and prints one markdown row per operation: guest
# instructions per call. A further board is one more entry in `targets` and `labels`.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(thumbv7em-none-eabihf thumbv8m.main-none-eabihf thumbv7m-none-eabi thumbv6m-none-eabi)
labels=(M4F M33 M3 M0)
dir="${CARGO_TARGET_DIR:-target}/icount"
mkdir -p "$dir"
for t in "${targets[@]}"; do
  : > "$dir/$t.txt"
  for e in fw_icount fw_icount_estimation; do
    cargo run -q --profile firmware --example "$e" --target "$t" > "$dir/$e-$t.txt"
    grep -q '^done' "$dir/$e-$t.txt"
    cat "$dir/$e-$t.txt" >> "$dir/$t.txt"
  done
done
header="| operation"; rule="|---"
for i in "${!targets[@]}"; do
  header="$header | ${labels[$i]} (${targets[$i]})"; rule="$rule|---:"
done
echo "$header |"; echo "$rule|"
awk '/^icount /{print $2}' "$dir/${targets[0]}.txt" | while read -r op; do
  row="| \`$op\`"
  for t in "${targets[@]}"; do
    row="$row | $(awk -v op="$op" '$1=="icount" && $2==op {print $3}' "$dir/$t.txt")"
  done
  echo "$row |"
done
