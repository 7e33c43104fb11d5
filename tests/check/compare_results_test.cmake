# CTest test of fem-compare-results itself: two runs that differ only in their timings compare equal,
# and a run that differs in one result, in each kind of file, does not.
#   cmake -DCOMPARE=<fem-compare-results> -DOUT=<scratch folder> -P compare_results_test.cmake
file(REMOVE_RECURSE ${OUT})

# One run's files: a runs.json, a table with a wall-time column, a Markdown table with a wall-time and
# a rate column (as finger_damping's table-3-2.md). `wall` stands for the timings, the rest for results.
function(write_run dir wall peak steps dat_value)
  file(WRITE ${dir}/runs.json
       "{\"runs\":[{\"name\":\"a\",\"wall_s\":${wall},\"s_per_iteration\":${wall},\"peak_mm\":${peak}}]}")
  file(WRITE ${dir}/series.dat "# t_s force_N wall_s\n0 ${dat_value} ${wall}\n")
  file(WRITE ${dir}/table-3-2.md
       "# Table\n\n| case | steps | wall s (+ set-up) | element-cycles/s |\n|---|---|---|---|\n"
       "| A | ${steps} | ${wall} (+0.1) | ${wall}e6 |\n\nText after the table.\n")
endfunction()

function(expect_exit dir expected why)
  execute_process(COMMAND ${COMPARE} ${OUT}/serial ${dir} RESULT_VARIABLE rc OUTPUT_VARIABLE text)
  if(NOT rc EQUAL expected)
    message(FATAL_ERROR "fem-compare-results serial vs ${dir}: exit ${rc}, expected ${expected} (${why}):\n${text}")
  endif()
endfunction()

write_run(${OUT}/serial 1.5 2.0 100 7)
write_run(${OUT}/timings 9.25 2.0 100 7)
write_run(${OUT}/json-result 1.5 2.5 100 7)
write_run(${OUT}/dat-result 1.5 2.0 100 8)
write_run(${OUT}/md-result 1.5 2.0 101 7)
expect_exit(${OUT}/timings 0 "only the timings differ")
expect_exit(${OUT}/json-result 1 "runs.json's peak_mm differs")
expect_exit(${OUT}/dat-result 1 "series.dat's force differs")
expect_exit(${OUT}/md-result 1 "table-3-2.md's steps differ")
