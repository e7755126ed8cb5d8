# Writes input.md (from `granular-dsmc --print-reference` and --print-defaults), observables.md (from
# --print-observables) and
# validation_results.md (the reports the validation programs wrote in this build tree).
file(READ ${TABLES} tables)
# The help texts are plain text: a `<file stem>` is not an HTML tag.
string(REPLACE "<" "&lt;" tables "${tables}")
string(REPLACE ">" "&gt;" tables "${tables}")
execute_process(COMMAND ${TEMPLATE_CMD} --print-defaults OUTPUT_VARIABLE template)
file(WRITE ${OUT}/input.md "# Input reference {#input}\n\n"
  "Generated from the parameter tables of `src/io/config_fields.cpp` (the same tables the reader uses).\n\n"
  "${tables}\n## Template (`granular-dsmc --print-defaults`)\n\n```\n${template}```\n")
execute_process(COMMAND ${TEMPLATE_CMD} --print-observables OUTPUT_VARIABLE observables)
file(WRITE ${OUT}/observables.md "# Observables {#observables_page}\n\n"
  "Generated from the table of observables of `src/model/observables.cpp` (`granular-dsmc --print-observables`), "
  "the table the sampling, the writer, the units, the sweep tables and `--compare` read. A series is written as "
  "`/observables/<name>` with `step`, `time`, `value` and `error` (\\ref output_observables \"the output page\"); the "
  "others as the output page describes.\n\n${observables}\n")
file(GLOB reports ${REPORTS}/*.report.txt)
set(body "# Validation results {#validation_results}\n\n"
  "The reports below were written by the validation programs when ctest ran them in this build "
  "tree (`ctest -L quick` or `ctest -L paper`). Each line: measured value +- its standard error over "
  "replicas, theory, difference in standard errors, tolerance. The figures drawn from these runs: "
  "`cmake --build build --target figures` (PDF and PNG in build/figures/); \\ref validation_summary "
  "shows them beside the measured numbers.\n\n")
if(NOT reports)
  string(APPEND body "No validation has been run in this build tree yet.\n")
endif()
foreach(r ${reports})
  get_filename_component(name ${r} NAME)
  file(READ ${r} text)
  string(APPEND body "## ${name}\n\n```\n${text}```\n\n")
endforeach()
file(WRITE ${OUT}/validation_results.md "${body}")
