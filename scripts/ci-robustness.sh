#!/usr/bin/env bash
# The robustness checks of docs/robustness.md, in order, each timed:
#   1. scripts/ci-sanitizers.sh      whole ctest suite under ASan+UBSan+LSan (clang -O1)
#   2. scripts/ci-fuzz.sh            libFuzzer on the glTF loader (.gltf, .glb: $MVCL_FUZZ_SECONDS each),
#                                    the OBJ, STL and PLY readers, session files and viewer scripts (half that each)
#   3. scripts/ci-flag-invariance.sh robustness digest identical across compilers and flags
#   4. scripts/ci-tsan.sh            the concurrent parts under ThreadSanitizer (clang -O1, an
#                                    instrumented oneTBB), and a deliberate race reported
# Needs the base packages of scripts/bootstrap.sh; each script installs what else it needs.
# Every step runs even when an earlier one failed (they are independent, and CI should show all
# findings at once); the exit status is non-zero if any failed. Budget on 2 cores: ~32 minutes.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

total_start=$(date +%s)
summary=()
failed=0
for step in ci-sanitizers ci-fuzz ci-flag-invariance ci-tsan; do
  echo "=== ci-robustness: $step"
  start=$(date +%s)
  if "$here/$step.sh"; then result=passed; else result=FAILED; failed=1; fi
  summary+=("$step $result in $(($(date +%s) - start)) s")
done
echo "=== ci-robustness: $(((failed)) && echo FAILED || echo passed) in $(($(date +%s) - total_start)) s"
printf '    %s\n' "${summary[@]}"
exit "$failed"
