#!/usr/bin/env bash
# usage: run_libfuzzer.sh FUZZER CORPUS SECONDS
# libFuzzer over the readers for SECONDS in all. The reader's crash guard (io/h5.cpp, docs/design.md
# §2.3) ends the process with exit 2 and its "damaged file: the HDF5 library crashed" message when the
# library itself crashes on a damaged file without checksums: that is the designed outcome (exit 2
# with a message), not a finding, so the fuzzer is started again for the time left. Any other exit,
# or a sanitizer report, fails.
set -uo pipefail
fuzzer=$1 corpus=$2 seconds=$3
log=$(dirname "$fuzzer")/libfuzzer.log
deadline=$((SECONDS + seconds))
guarded=0
while ((SECONDS < deadline)); do
  left=$((deadline - SECONDS))
  "$fuzzer" -max_total_time="$left" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$(dirname "$fuzzer")/" "$corpus" > "$log" 2>&1
  rc=$?
  if ((rc == 0)); then
    tail -n 12 "$log"
    break
  fi
  if ((rc == 2)) && tail -n 1 "$log" | grep -q "damaged file: the HDF5 library crashed" &&
     ! grep -q "ERROR: AddressSanitizer\|runtime error:\|ERROR: libFuzzer" "$log"; then
    guarded=$((guarded + 1))
    echo "crash guard: $(tail -n 1 "$log")"
    continue
  fi
  tail -n 60 "$log"
  echo "libFuzzer: exit $rc (a finding; inputs in $(dirname "$fuzzer")/)"
  exit 1
done
echo "libFuzzer: ${seconds} s, ${guarded} restart(s) after the crash guard's exit 2"
