# Benchmark B1 (BENCHMARKS.md, 1D ghost forces) in its reduced CI form: the
# verification script runs the program for h = δ/4, δ/8, Lc = 3, 6, the linear
# and cubic profiles and both coupling rules, compares with the continuum
# formulas of THEORY §3.2 and exits non-zero if a criterion that applies to the
# reduced set fails (the full study: verification/b1_ghost_forces.py without
# --quick, results in verification/results/).
add_test(NAME verification_b1_quick
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/verification/b1_ghost_forces.py --quick
          --perimorph $<TARGET_FILE:perimorph_cli> --out ${CMAKE_CURRENT_BINARY_DIR}/b1_quick)
set_tests_properties(verification_b1_quick PROPERTIES TIMEOUT 300 LABELS verification)
