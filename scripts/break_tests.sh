#!/bin/bash
# Breaks the subject of each "test that can fail" of issue 11 once, in a scratch git worktree of
# HEAD, and records in $LOG that its test then fails (and passes before). Slow: a full build.
# Usage: scripts/break_tests.sh   (W=DIR for the worktree, LOG=FILE for the record)
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
W=${W:-$(mktemp -d)/wt}
LOG=${LOG:-$W.log}
: > $LOG
cd "$root" && git worktree add -f --detach "$W" HEAD >/dev/null
cd "$W"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DLUCERNA_CUDA=OFF -DLUCERNA_BENCH=OFF >/dev/null
nice -n 15 cmake --build build -j2 >/dev/null 2>&1 || echo "baseline build failed" >> $LOG
run() {  # name, ctest regex
  echo "=== $1" >> $LOG
  ctest --test-dir build -R "$2" --timeout 300 2>&1 | grep -E "Passed|Failed|Skipped|tests passed|Not Run|\*\*\*" >> $LOG
}
echo "##### baseline" >> $LOG
run baseline '^(ParseErrors.FuzzRegressionsGiveTheirExpectedOutcome|InfoCommand.ExitCodesAndOutput|Cli.ConvergeWritesCsvReportAndFallingError|Camera.GetCameraSampleUsesFiveDimensions|Chi2Harness.InvalidTestsFailBothWays|Diff\.)'

echo "##### 1. fuzz/regressions folder removed" >> $LOG
mv fuzz/regressions "$W.regressions"
run fuzzreg 'ParseErrors.FuzzRegressionsGiveTheirExpectedOutcome'
mv "$W.regressions" fuzz/regressions
echo "##### 1b. a new regression input without an expected outcome" >> $LOG
echo 'Shape "sphere"' > fuzz/regressions/zz_unlisted.pbrt
run fuzzreg2 'ParseErrors.FuzzRegressionsGiveTheirExpectedOutcome'
rm fuzz/regressions/zz_unlisted.pbrt

echo "##### 2. lucerna binary missing" >> $LOG
mv build/lucerna build/lucerna.bak
run info 'InfoCommand.ExitCodesAndOutput'
run diffbin '^Diff\.'
mv build/lucerna.bak build/lucerna

echo "##### 3. report script writes no index.html (exits 0 at once)" >> $LOG
cp scripts/make_report.py "$W.make_report.py"
sed -i '0,/^import argparse/s//import sys; sys.exit(0)\nimport argparse/' scripts/make_report.py
run converge 'Cli.ConvergeWritesCsvReportAndFallingError'
cp "$W.make_report.py" scripts/make_report.py

echo "##### 4. GetCameraSample skips the time dimension" >> $LOG
sed -i 's/    cs.time = sampler.Get1D();/    cs.time = 0;/' src/lucerna/camera/camera.h
nice -n 15 cmake --build build -j2 --target test_sampling >/dev/null 2>&1
run camera 'Camera.GetCameraSampleUsesFiveDimensions'
git checkout -q src/lucerna/camera/camera.h
nice -n 15 cmake --build build -j2 --target test_sampling >/dev/null 2>&1

echo "##### 5. chi-square with too few cells returns p = 1 (the old behaviour)" >> $LOG
sed -i 's/        r.p = kNaN;/        r.p = 1;/' tests/support/chi2.cpp
nice -n 15 cmake --build build -j2 --target test_sampling >/dev/null 2>&1
run chi2 'Chi2Harness.InvalidTestsFailBothWays'
git checkout -q tests/support/chi2.cpp
nice -n 15 cmake --build build -j2 --target test_sampling >/dev/null 2>&1

echo "##### 6. cmd_diff.cpp deleted from the build" >> $LOG
git rm -q apps/cmd_diff.cpp
nice -n 15 cmake --build build -j2 --target lucerna > "$W.diffbuild.txt" 2>&1; echo "build rc=$?" >> $LOG
grep -E "undefined reference|error" "$W.diffbuild.txt" | head -3 >> $LOG
run diffgone '^Diff\.'
git checkout -q HEAD -- apps/cmd_diff.cpp
echo "##### done" >> $LOG
echo "record: $LOG (worktree $W: remove with git worktree remove --force $W)"
