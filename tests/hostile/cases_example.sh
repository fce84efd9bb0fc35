# A baseline: the good input runs and writes its monitors.
hostile_baseline_good_input_runs() {
  emc_good_input in.xml
  expect_exit 0 "$EMC" in.xml --output out
  test -s out/monitors.csv
}
