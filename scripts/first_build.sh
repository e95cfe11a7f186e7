#!/usr/bin/env bash
# Times the README's first builds from an empty target directory (dependencies already
# downloaded): `cargo build --release` and `cargo test --all-features --no-run`, in a clean
# clone of the committed tree, one after the other. Prints the commit, the machine's cores
# and 1-minute load average before each build, and each build's wall-clock and CPU times
# (user + system, children included), the figures the README quotes.
#
#   scripts/first_build.sh
set -euo pipefail
cd "$(dirname "$0")/.."
commit="$(git rev-parse --short HEAD)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
git clone -q . "$work/tree"
cd "$work/tree"
echo "commit $commit, $(nproc) cores"
for build in "cargo build --release" "cargo test --all-features --no-run"; do
    load="$(cut -d' ' -f1 /proc/loadavg)"
    start="$(date +%s.%N)"
    cpu_before="$(awk '{print $14 + $15 + $16 + $17}' /proc/$$/stat)"
    # The build's output is not the point: only its times are printed.
    CARGO_TARGET_DIR="$work/target" $build >/dev/null 2>&1
    cpu_after="$(awk '{print $14 + $15 + $16 + $17}' /proc/$$/stat)"
    wall="$(echo "$(date +%s.%N) - $start" | bc)"
    cpu="$(echo "($cpu_after - $cpu_before) / $(getconf CLK_TCK)" | bc)"
    printf '%s: %d min %02d s wall, %d s of CPU time (load average %s at the start)\n' \
        "$build" "$(echo "$wall / 60" | bc)" "$(echo "$wall % 60 / 1" | bc)" "$cpu" "$load"
    rm -rf "$work/target"
done
