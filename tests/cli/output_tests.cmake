# Issue 18, item 6: output that no other run can spoil.
# A full disk (a 2 MB tmpfs mounted for the test; skipped, exit 77, where the
# machine does not allow mounting): the run stops with the system's reason and
# exit status 5, and the files stay in step (CSV rows = PVD entries = VTU
# files, no temporary left).
set(PM_OUTPUT_OUT ${CMAKE_CURRENT_BINARY_DIR}/cli_output/output)
add_test(NAME cli_full_disk_stops_with_the_reason_and_files_in_step
  COMMAND sh -c "d=\"$2/tmpfs\"; mkdir -p \"$d\"; mount -t tmpfs -o size=2M tmpfs \"$d\" 2>/dev/null || exit 77; \
\"$0\" run \"$1\" -o \"$d\" --quiet; echo \"exit status $?\"; \
r=$(($(wc -l < \"$d/fracture_plate.csv\") - 1)); p=$(grep -c '<DataSet' \"$d/fracture_plate.pvd\"); \
v=$(ls \"$d\" | grep -c '[.]vtu$'); t=$(ls \"$d\" | grep -c '[.]tmp$'); \
umount \"$d\"; \
if [ $r -eq $p ] && [ $p -eq $v ] && [ $t -eq 0 ] && [ $r -gt 0 ]; then echo \"files in step: $r rows\"; \
else echo \"out of step: $r rows, $p entries, $v VTU, $t temporaries\"; fi"
          $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml ${PM_OUTPUT_OUT})
set_tests_properties(cli_full_disk_stops_with_the_reason_and_files_in_step PROPERTIES
  PASS_REGULAR_EXPRESSION "No space left on device.*exit status 5\nfiles in step: [0-9]+ rows"
  SKIP_RETURN_CODE 77 TIMEOUT 120)

# A second run into the folder and basename of a running one is refused at
# once (exit status 5, naming the first run's process); the first is unharmed.
add_test(NAME cli_second_writer_of_an_output_set_is_refused
  COMMAND sh -c "rm -rf \"$2/shared\"; \"$0\" run \"$1\" -o \"$2/shared\" --quiet & pid=$!; i=0; \
while [ ! -f \"$2/shared/fracture_plate.csv\" ] && [ $i -lt 600 ]; do sleep 0.05; i=$((i+1)); done; \
\"$0\" run \"$1\" -o \"$2/shared\" --quiet; echo \"second: exit status $?\"; wait $pid; echo \"first: exit status $?\""
          $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml ${PM_OUTPUT_OUT})
set_tests_properties(cli_second_writer_of_an_output_set_is_refused PROPERTIES
  PASS_REGULAR_EXPRESSION "another run \\(process [0-9]+\\) is writing fracture_plate[.][*].*second: exit status 5\nfirst: exit status 0"
  TIMEOUT 120)

# Issue 18, item 5: a reaction or an energy that is NaN or Inf stops the run at
# that increment, written as it came out, naming the increment and the
# columns (exit status 3).
add_test(NAME cli_non_finite_energy_stops_the_run_naming_the_columns
  COMMAND sh -c "rm -rf \"$2\"; \"$0\" run \"$1\" -o \"$2\" --quiet; echo \"exit status $?\"; \
echo \"$(($(wc -l < \"$2/overflow_bar.csv\") - 1)) rows\""
          $<TARGET_FILE:perimorph_cli> ${CMAKE_CURRENT_SOURCE_DIR}/data/runs/overflow_bar.toml ${PM_OUTPUT_OUT}/overflow)
set_tests_properties(cli_non_finite_energy_stops_the_run_naming_the_columns PROPERTIES
  PASS_REGULAR_EXPRESSION "solver error: increment 1/2 \\(load factor 0.5\\): strain_energy = inf, external_work = inf \\(CSV columns\\) although the solution is finite.*exit status 3\n1 rows"
  TIMEOUT 60)
