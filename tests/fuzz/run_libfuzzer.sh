#!/usr/bin/env bash
# usage: run_libfuzzer.sh FUZZER CORPUS SECONDS
# libFuzzer over the readers for SECONDS in all. The reader's crash guard (io/h5.cpp, docs/design.md
# §2.3) ends the process with exit 2 and its "damaged file: the HDF5 library crashed" message when the
# library itself crashes on a damaged file without checksums: that is the designed outcome (exit 2
# with a message), not a finding, so the fuzzer is started again for the time left; so is ASan's report of
# the same library reading out of bounds (library_read below). Any other exit, or sanitizer report, fails.
set -uo pipefail
fuzzer=$1 corpus=$2 seconds=$3
# The HDF5 library reading out of bounds while it walks a damaged file's unverifiable metadata is the
# crash the guard is for, caught earlier by ASan's memcpy check: a READ whose first frame past ASan's
# interceptor is in libhdf5, from memory that granwave did not allocate (no granwave:: frame, nor the
# fuzzer's entry point, in an "allocated by" stack; not the bare word: a checkout's path may hold it).
# A write, a read from granwave's memory, or a fault in granwave's code stays a finding. ASan names the
# allocated chunk beside the address when there is one, else a freed one: a freed chunk named (a past
# input's buffer, "previously allocated by" the entry point) says no live buffer of anyone's is beside
# the read, so its stack says nothing of whose buffer the library ran past (a use-after-free stays a finding).
library_read() {
  local log=$1
  grep -q "^READ of size" "$log" || return 1
  grep -A2 "^READ of size" "$log" | grep -m1 "#1 " | grep -q "libhdf5" || return 1
  if grep -q "ERROR: AddressSanitizer: heap-buffer-overflow" "$log" && grep -q "^freed by thread" "$log"; then
    return 0
  fi
  ! awk '/allocated by thread/ {stack = 1; next} stack && /^$/ {stack = 0} stack' "$log" |
    grep -q "granwave::\|LLVMFuzzerTestOneInput"
}
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
     ! grep -q "runtime error:\|ERROR: libFuzzer" "$log" && { ! grep -q "ERROR: AddressSanitizer" "$log" || library_read "$log"; }; then
    guarded=$((guarded + 1))
    echo "crash guard: $(tail -n 1 "$log")"
    continue
  fi
  # The report's head (what was accessed, where, and whose memory) before its tail: CI keeps a log's end.
  grep -m1 -A40 "ERROR: AddressSanitizer\|runtime error:\|ERROR: libFuzzer" "$log"
  echo "..."
  tail -n 30 "$log"
  echo "libFuzzer: exit $rc (a finding; inputs in $(dirname "$fuzzer")/)"
  exit 1
done
echo "libFuzzer: ${seconds} s, ${guarded} restart(s) after the crash guard's exit 2"
