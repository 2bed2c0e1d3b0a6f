#!/usr/bin/env bash
# Instructions executed by examples/instruction_counts.rs at two commits, side
# by side (valgrind's callgrind; one thread). Usage:
#   tools/compare_instructions.sh OLD_REV NEW_REV
# Builds each revision in a worktree under target/instructions/ with the
# example of NEW_REV, so that both run the same driver.
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1 new=$2
example=$(pwd)/examples/instruction_counts.rs
for rev in "$old" "$new"; do
  dir=target/instructions/$rev
  [ -d "$dir" ] || git worktree add -q --detach "$dir" "$rev"
  mkdir -p "$dir/examples" && cp "$example" "$dir/examples/"
  (cd "$dir" && cargo build -q --release --example instruction_counts)
done
printf '%-10s %16s %16s %8s  %s\n' phase "$old" "$new" change "same result"
for phase in setup gain integrate laser; do
  declare -A count out
  for rev in "$old" "$new"; do
    bin=target/instructions/$rev/target/release/examples/instruction_counts
    err=$(mktemp)
    out[$rev]=$(RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$phase" 2>"$err")
    count[$rev]=$(grep -o 'Collected : [0-9]*' "$err" | grep -o '[0-9]*$')
    rm -f "$err"
  done
  change=$(python3 -c "print(f'{(${count[$new]} / ${count[$old]} - 1) * 100:+.2f} %')")
  same=$([ "${out[$old]}" = "${out[$new]}" ] && echo yes || echo NO)
  printf '%-10s %16s %16s %8s  %s\n' "$phase" "${count[$old]}" "${count[$new]}" "$change" "$same"
done
