# Issue 18, item 2: a run killed at any moment (SIGKILL: no handler runs)
# continues from its last checkpoint with `run --restart DIR`, and its output
# (CSV rows without the wall times, PVD, VTU files) is the uninterrupted
# run's, bit for bit (compare_runs.py). The edge-cracked plate example breaks
# bonds in increments 2 to 11; the kill comes once the checkpoint of
# increment 3 exists (checkpoint every 3 increments), so the continued run
# breaks bonds, and whatever the killed run wrote after the checkpoint is cut
# off. A SIGTERM between increments writes a checkpoint too
# (tests/run/restart_test.cpp).
set(PM_RESTART_OUT ${CMAKE_CURRENT_BINARY_DIR}/cli_output/restart)
add_test(NAME cli_restart_full_run
  COMMAND $<TARGET_FILE:perimorph_cli> run ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml
          -o ${PM_RESTART_OUT}/full --quiet)
set_tests_properties(cli_restart_full_run PROPERTIES FIXTURES_SETUP restart_full TIMEOUT 120)

add_test(NAME cli_restart_after_sigkill_continues_bit_for_bit
  COMMAND sh -c "rm -rf \"$2/killed\"; \"$0\" run \"$1\" -o \"$2/killed\" --quiet --checkpoint-every 3 & pid=$!; \
i=0; while [ ! -f \"$2/killed/fracture_plate.checkpoint\" ] && [ $i -lt 1200 ]; do sleep 0.05; i=$((i+1)); done; \
kill -KILL $pid; wait $pid; echo \"killed: exit status $?\"; \
\"$0\" run \"$1\" -o \"$2/killed\" --restart \"$2/killed\" || exit 1; \
/usr/bin/python3 \"$3\" \"$2/full\" \"$2/killed\""
          $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml ${PM_RESTART_OUT}
          ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_runs.py)
set_tests_properties(cli_restart_after_sigkill_continues_bit_for_bit PROPERTIES
  FIXTURES_REQUIRED restart_full
  PASS_REGULAR_EXPRESSION "killed: exit status 137.*continued after increment [0-9]+ .*[0-9]+ files compared, 0 differ"
  TIMEOUT 180)

# A bad value on the command line is an input error: exit status 2 with
# CLI11's message (not CLI11's own exit codes).
add_test(NAME cli_bad_checkpoint_every_is_an_input_error
  COMMAND sh -c "\"$0\" run \"$1\" --checkpoint-every -2 --quiet; echo \"exit status $?\""
          $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml)
set_tests_properties(cli_bad_checkpoint_every_is_an_input_error PROPERTIES
  PASS_REGULAR_EXPRESSION "--checkpoint-every: Value -2 not in range 0 to 2147483647.*exit status 2" TIMEOUT 30)
