#!/usr/bin/env bash
# Fresh Debian 12: install dependencies, build everything (Release: renderer, tests, benchmarks,
# and the CUDA backend whenever nvcc exists), run the whole test suite, then the sanitizer build
# of the unit tests and the fuzzers (bounded time).
# Environment: FUZZ_SECONDS (default 30 per target), SKIP_SANITIZERS=1, SKIP_FUZZ=1,
# LUCERNA_CUDA=AUTO|ON|OFF (default AUTO: compiled when nvcc is found),
# LUCERNA_CUDA_ARCHITECTURES (default 90: sm_90 machine code and compute_90 PTX).
set -uo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
status=0
step() { echo; echo "==== $* ($(( $(date +%s) - start ))s)"; }

step "dependencies"
scripts/setup.sh all || exit 1

# The CUDA backend is built as machine code for sm_90 (plus its PTX) with or without a GPU, so
# that CI runs ptxas on the megakernel as a GPU user's build does: whole-program ptxas once needed
# over 24 GB there (now relocatable code, 1.9 GB), which a PTX-only build (90-virtual) cannot show.
LUCERNA_CUDA_ARCHITECTURES=${LUCERNA_CUDA_ARCHITECTURES:-90}
step "build (Release; CUDA architectures ${LUCERNA_CUDA_ARCHITECTURES})"
# Every option explicit: build/ may have been configured by scripts/demo.sh (renderer only).
scripts/build.sh -DLUCERNA_TESTS=ON -DLUCERNA_BENCH=ON -DLUCERNA_CUDA="${LUCERNA_CUDA:-AUTO}" \
                 -DCMAKE_CUDA_ARCHITECTURES="${LUCERNA_CUDA_ARCHITECTURES}" || exit 1

step "unit, integration and reference tests"
ctest --test-dir build --output-on-failure -j "$(nproc)" --timeout 900 || status=1

if [ "${SKIP_SANITIZERS:-0}" != 1 ]; then
  step "AddressSanitizer + UBSan build of the unit tests"
  # (not tests/mpi: Open MPI's own allocations that live until exit read as leaks to LeakSanitizer)
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLUCERNA_SANITIZE=ON -DLUCERNA_CUDA=OFF \
        -DLUCERNA_BENCH=OFF >/dev/null && cmake --build build-asan -j "$(nproc)" || exit 1
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --timeout 900 -LE "slow|reference|mpi" || status=1
fi

if [ "${SKIP_FUZZ:-0}" != 1 ] && [ -x fuzz/run.sh ]; then
  step "fuzzing (${FUZZ_SECONDS:-30}s per target)"
  fuzz/run.sh "${FUZZ_SECONDS:-30}" || status=1
fi

step "done: status $status"
exit $status
