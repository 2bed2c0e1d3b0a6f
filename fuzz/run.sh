#!/usr/bin/env bash
# Run every fuzz target for SECONDS (default 60), seed 1, on its seeded corpus
# (bash fuzz/seed.sh first) and print each one's last status line: the
# executions, the coverage and features reached. Needs a nightly toolchain
# and cargo-fuzz; says so and exits 0 where they are absent.
set -euo pipefail
cd "$(dirname "$0")"
seconds=${1:-60}
if ! cargo +nightly --version >/dev/null 2>&1 || ! cargo +nightly fuzz --version >/dev/null 2>&1; then
    echo "fuzz/run.sh: no nightly toolchain with cargo-fuzz here: the fuzz targets were not run"
    exit 0
fi
for t in carmen sonar_text map_file map_file_entries image ros_map_yaml yaml_nesting geojson aria; do
    mkdir -p "corpus/$t"
    log=$(mktemp)
    if ! cargo +nightly fuzz run "$t" "corpus/$t" -- -max_total_time="$seconds" -seed=1 -rss_limit_mb=2048 -timeout=10 -max_len=65536 >"$log" 2>&1; then
        tail -40 "$log"
        echo "fuzz/run.sh: $t failed (its input is in fuzz/artifacts/$t/)"
        exit 1
    fi
    echo "$t: $(grep -E '^#[0-9]+' "$log" | tail -1)"
    rm -f "$log"
done
