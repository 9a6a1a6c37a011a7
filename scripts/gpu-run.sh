#!/usr/bin/env bash
# On the lent GPU machine: runs one named suite of scripts/gpu/ from the repository root.
#   scripts/gpu-run.sh            the whole test suite on CUDA and NVIDIA OpenCL, then benchmarks (suite "tests")
#   scripts/gpu-run.sh SUITE      one suite; each file's header says what it measures and what to carry
#   scripts/gpu-run.sh --list     the suites with their first comment line
# Environment variables (OUT, DEVICES, BENCH_*, TESTS, ...) reach the suite unchanged.
set -uo pipefail
cd "$(dirname "$0")/.."
suites=scripts/gpu
if [[ ${1:-} == --list || ${1:-} == -h || ${1:-} == --help ]]; then
  for f in "$suites"/*.sh; do
    printf '%-16s %s\n' "$(basename "$f" .sh)" "$(sed -n '2s/^# *//p' "$f")"
  done
  exit 0
fi
suite=${1:-tests}
if [[ ! -f $suites/$suite.sh ]]; then
  echo "gpu-run: no suite '$suite' (choose one of: $(cd "$suites" && ls -- *.sh | sed 's/\.sh$//' | tr '\n' ' '))" >&2
  exit 2
fi
shift $(($# > 0 ? 1 : 0))
exec bash "$suites/$suite.sh" "$@"
