# cmake -DEOMGEN=... -DMODEL=... -DEXPECTED=... -DACTUAL=... -P CompareGenerated.cmake
# Regenerates one shipped model and fails if it differs from the checked-in header.
get_filename_component(actual_dir ${ACTUAL} DIRECTORY)
file(MAKE_DIRECTORY ${actual_dir})
execute_process(COMMAND ${EOMGEN} generate ${MODEL} -o ${ACTUAL} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "eomgen generate ${MODEL} failed with status ${status}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${EXPECTED} ${ACTUAL} RESULT_VARIABLE differ)
if(differ)
  message(FATAL_ERROR "${EXPECTED} is out of date with ${MODEL} or the generator: "
                      "run `cmake --build <build dir> --target regenerate` and commit generated/")
endif()
