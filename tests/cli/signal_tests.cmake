# Issue 18, item 6: SIGTERM (and SIGINT) stop a run between solves with a
# message naming the increment and what is kept, exit status 128 + signal, and
# the output in step: as many CSV rows as PVD entries as VTU files (the example
# writes every increment). The signal is sent once the run's CSV exists (the
# handlers are installed before it is made); the example needs many seconds
# more to finish.
set(PM_SIGNAL_OUT ${CMAKE_CURRENT_BINARY_DIR}/cli_output/signal)
add_test(NAME cli_sigterm_stops_between_solves_with_files_in_step
  COMMAND sh -c "rm -rf \"$2\"; \"$0\" run \"$1\" -o \"$2\" --quiet & pid=$!; i=0; \
while [ ! -f \"$2/fracture_plate.csv\" ] && [ $i -lt 600 ]; do sleep 0.1; i=$((i+1)); done; \
kill -TERM $pid; wait $pid; echo \"exit status $?\"; \
r=$(($(wc -l < \"$2/fracture_plate.csv\") - 1)); p=$(grep -c '<DataSet' \"$2/fracture_plate.pvd\"); \
v=$(ls \"$2\" | grep -c '[.]vtu$'); \
if [ $r -eq $p ] && [ $p -eq $v ]; then echo \"files in step: $r rows\"; else echo \"out of step: $r $p $v\"; fi"
          $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml ${PM_SIGNAL_OUT})
set_tests_properties(cli_sigterm_stops_between_solves_with_files_in_step PROPERTIES
  PASS_REGULAR_EXPRESSION
  "stopped: SIGTERM received: the run stops in increment [0-9]+/30 .*that increment is not written.*exit status 143\nfiles in step"
  TIMEOUT 120)
