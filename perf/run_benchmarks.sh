#!/usr/bin/env bash
# Builds and runs the kernel, contact-search and assembly benchmarks, writes
# perf/results/kernels.json, perf/results/search.json, perf/results/assembly.json and the table in
# perf/README.md. Usage: bash perf/run_benchmarks.sh [--short]   (--short: what CI can afford)
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-perf -G Ninja -DCMAKE_BUILD_TYPE=Release -DEMC_ENABLE_TESTS=OFF > /dev/null
cmake --build build-perf -j "$(nproc)" --target bench_kernels bench_search bench_assembly
min_time=1.0
[ "${1:-}" = "--short" ] && min_time=0.05
mkdir -p perf/results
build-perf/bin/bench_kernels --benchmark_min_time="$min_time" \
  --benchmark_out=perf/results/kernels.json --benchmark_out_format=json
build-perf/bin/bench_search --benchmark_min_time="$min_time" \
  --benchmark_out=perf/results/search.json --benchmark_out_format=json
build-perf/bin/bench_assembly --benchmark_min_time="$min_time" \
  --benchmark_out=perf/results/assembly.json --benchmark_out_format=json
/usr/bin/python3 perf/kernels_table.py perf/results/kernels.json perf/results/search.json \
  perf/results/assembly.json
