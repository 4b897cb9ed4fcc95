#!/bin/sh
# Regression for the Verilator harness: runs every sim/tests/*.run and compares the
# trace, the summary (minus the wall-clock speed), stderr and the exit status with
# sim/tests/NAME.expect.   usage: tests/run_tests.sh [HARNESS] [--update]
# Run from sim/ (the run files name their files relative to it).
cd "$(dirname "$0")/.." || exit 2
bin=${1:-build/Vbitbyte_cpu}
update=$2
[ -x "$bin" ] || { echo "no harness at $bin (make -C sim harness)"; exit 2; }
mkdir -p build/tests
fail=0
for run in tests/*.run; do
  name=$(basename "$run" .run)
  out=build/tests/$name.out
  rm -f "build/tests/$name.csv"
  "$bin" "$run" >build/tests/$name.stdout 2>build/tests/$name.stderr
  rc=$?
  {
    echo "--- trace"; cat "build/tests/$name.csv" 2>/dev/null
    echo "--- summary"; sed 's/^stat wall_s .*/stat wall_s */' build/tests/$name.stdout
    echo "--- stderr"; cat build/tests/$name.stderr
    echo "--- exit $rc"
  } >"$out"
  if [ "$update" = "--update" ]; then
    cp "$out" "tests/$name.expect"
  elif ! diff -u "tests/$name.expect" "$out"; then
    echo "FAIL $name"; fail=1
  fi
done
[ $fail = 0 ] && echo "harness tests passed"
exit $fail
