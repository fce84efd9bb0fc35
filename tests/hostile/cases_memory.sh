# The peak resident memory per rank that a successful run prints ("emcontact: peak resident
# memory per rank: A B MiB (rank 0 first)"), checked against an independent measurement of the
# same quantity: GNU time's maximum resident set of the processes it waited for (the largest
# rank; mpirun itself is far smaller than a rank).

# peak_line_numbers FILE: the numbers of the line, one per line of output.
peak_line_numbers() {
  sed -n 's/^emcontact: peak resident memory per rank: \(.*\) MiB (rank 0 first)$/\1/p' "$1" | tr ' ' '\n'
}

hostile_peak_memory_per_rank_two_ranks() {
  emc_good_input in.xml
  expect_exit_within 120 0 /usr/bin/time -f %M -o rss_kb.txt \
    "${MPIRUN[@]}" -np 2 "$EMC" in.xml --output out --set Output/plot=false
  mapfile -t mib < <(peak_line_numbers last.out)
  if [ "${#mib[@]}" -ne 2 ]; then
    echo "expected one peak memory line with 2 numbers (2 ranks), got: ${mib[*]}"
    grep -i "peak" last.out || true
    return 1
  fi
  local kb
  kb=$(tail -n 1 rss_kb.txt)
  # each rank at least 20 MiB (MPI, Kokkos and Trilinos alone map and touch more), the largest
  # within [time's - 16 MiB, time's + 1 MiB]: the line is taken just before the timer summary
  # and teardown, which add a few MiB at most; +1 for the rounding to MiB
  /usr/bin/python3 - "$kb" "${mib[@]}" <<'PY'
import sys
kb, mib = int(sys.argv[1]), [int(x) for x in sys.argv[2:]]
time_mib = kb / 1024
assert all(m >= 20 for m in mib), (mib, time_mib)
assert time_mib - 16 <= max(mib) <= time_mib + 1, (mib, time_mib)
PY
}
