# `perimorph gc`: the critical energy release rate of a crack plane (closed
# form, actual geometry, bulk window; diagnostics/effective_gc.hpp) and its messages
# for planes that cannot be used. The case is written here: a 4 x 4 plate
# (thickness 0.5), fully non-local, constant kernel, delta = 1, h = 1/4.
set(PM_GC_EXE $<TARGET_FILE:perimorph_cli>)
set(PM_GC_CASE ${CMAKE_CURRENT_BINARY_DIR}/gc_cli/plate.toml)
file(WRITE ${PM_GC_CASE} [=[
[mesh]
dim = 2
lower = [0.0, 0.0]
upper = [4.0, 4.0]
cells = [16, 16]

[model]
plane = "strain"
thickness = 0.5

[[material]]
name = "m"
E = 1.0

[nonlocal]
kernel = "constant"
horizon = 1.0
quadrature = 2

[alpha]
value = 1.0
]=])

# Plane strain, E = 1: c_hat = 128 / (5 pi), kappa = c_hat / 5 = 0.8148733; s_crit = 1e-3.
# The plane y = 2 is 4 long (area 4 x 0.5 = 2), its window 2 long (area 1).
add_test(NAME cli_gc_plate
  COMMAND ${PM_GC_EXE} gc ${PM_GC_CASE} --point 2 2 --normal 0 1 --s-crit 1e-3)
set_tests_properties(cli_gc_plate PROPERTIES
  PASS_REGULAR_EXPRESSION
  "closed form +G_c = 8\\.14873.e-07.*actual +G_c = [0-9.]+e-07.*bulk window +G_c = [0-9.]+e-07.*bonds +[1-9][0-9]* crossing.*area +plane 2\\.000000e\\+00, window 1\\.000000e\\+00"
  FAIL_REGULAR_EXPRESSION "error")

# Without --s-crit and without [fracture]: the figures are per s_crit^2.
add_test(NAME cli_gc_per_s_crit_squared
  COMMAND ${PM_GC_EXE} gc ${PM_GC_CASE} --point 2 2 0 --normal 0 1 0)
set_tests_properties(cli_gc_per_s_crit_squared PROPERTIES
  PASS_REGULAR_EXPRESSION "none given.*closed form +G_c = 8\\.14873.e-01 per s_crit\\^2")

add_test(NAME cli_gc_zero_normal
  COMMAND ${PM_GC_EXE} gc ${PM_GC_CASE} --point 2 2 --normal 0 0 0)
set_tests_properties(cli_gc_zero_normal PROPERTIES
  PASS_REGULAR_EXPRESSION "error: --normal .* is not a direction; give the crack plane's normal")

add_test(NAME cli_gc_plane_misses_the_body
  COMMAND ${PM_GC_EXE} gc ${PM_GC_CASE} --point 2 9 --normal 0 1)
set_tests_properties(cli_gc_plane_misses_the_body PROPERTIES
  PASS_REGULAR_EXPRESSION "error: the plane through .* does not cut the body .*choose a point inside the box")

# A point or normal with fewer numbers than the case has axes is an error, not a plane put at 0.
add_test(NAME cli_gc_point_short
  COMMAND ${PM_GC_EXE} gc ${PM_GC_CASE} --point 2 --normal 0 1)
set_tests_properties(cli_gc_point_short PROPERTIES
  PASS_REGULAR_EXPRESSION "error: --point has 1 number but .* is 2D: give one per axis \\(x y\\)")
add_test(NAME cli_gc_normal_short
  COMMAND ${PM_GC_EXE} gc ${PM_GC_CASE} --point 2 2 --normal 1)
set_tests_properties(cli_gc_normal_short PROPERTIES
  PASS_REGULAR_EXPRESSION "error: --normal has 1 number but .* is 2D")

add_test(NAME cli_gc_bad_s_crit
  COMMAND ${PM_GC_EXE} gc ${PM_GC_CASE} --point 2 2 --normal 0 1 --s-crit -1)
set_tests_properties(cli_gc_bad_s_crit PROPERTIES PASS_REGULAR_EXPRESSION "error: --s-crit must be a positive")

# s_crit from the case's [fracture] G_c: the closed form gives G_c back.
set(PM_GC_FRACTURE_CASE ${CMAKE_CURRENT_BINARY_DIR}/gc_cli/plate_fracture.toml)
file(READ ${PM_GC_CASE} pm_gc_plate)
file(WRITE ${PM_GC_FRACTURE_CASE} "${pm_gc_plate}\n[fracture]\nG_c = 2e-6\n")
add_test(NAME cli_gc_s_crit_from_case_G_c
  COMMAND ${PM_GC_EXE} gc ${PM_GC_FRACTURE_CASE} --point 2 2 --normal 0 1)
set_tests_properties(cli_gc_s_crit_from_case_G_c PROPERTIES
  PASS_REGULAR_EXPRESSION "s_crit +0\\.00156664 \\(\\[fracture\\] G_c.*closed form +G_c = 2\\.000000e-06 ")

# `info` of a case with [fracture]: the G_c factor (byte-stable for scripts)
# and the G_c, s_crit pair of the case.
add_test(NAME cli_info_fracture_G_c COMMAND ${PM_GC_EXE} info ${PM_GC_FRACTURE_CASE})
set_tests_properties(cli_info_fracture_G_c PROPERTIES
  PASS_REGULAR_EXPRESSION "G_c = 8\\.14873.e-01 \\* s_crit\\^2 .*\\[fracture\\] G_c = 2\\.000000e-06: s_crit = 0\\.00156664")
