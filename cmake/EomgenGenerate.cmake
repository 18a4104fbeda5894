# eomgen_add_model(TARGET name MODEL file.eom [OUTPUT header.hpp] [DEFINE n=8 ...] [LINEARIZATION])
#
# Generates a C++ header from a model file at build time and makes `name` an INTERFACE
# library that carries its include directory (and Eigen). The header is regenerated when
# the model file or the eomgen generator changes. LINEARIZATION also emits linearization_terms
# (eomgen generate --linearization) and links the runtime, whose eomrt::linearization turns
# them into A and B.
function(eomgen_add_model)
  cmake_parse_arguments(ARG "LINEARIZATION" "TARGET;MODEL;OUTPUT" "DEFINE" ${ARGN})
  if(NOT ARG_TARGET OR NOT ARG_MODEL)
    message(FATAL_ERROR "eomgen_add_model: TARGET and MODEL are required")
  endif()
  get_filename_component(model ${ARG_MODEL} ABSOLUTE)
  get_filename_component(stem ${ARG_MODEL} NAME_WE)
  if(NOT ARG_OUTPUT)
    set(ARG_OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/eomgen_generated/${ARG_TARGET}/${stem}.hpp)
  endif()
  get_filename_component(output ${ARG_OUTPUT} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_BINARY_DIR})
  get_filename_component(output_dir ${output} DIRECTORY)
  set(defines)
  foreach(definition IN LISTS ARG_DEFINE)
    list(APPEND defines --define ${definition})
  endforeach()
  if(ARG_LINEARIZATION)
    list(APPEND defines --linearization)
  endif()
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${output_dir}
    COMMAND eomgen::eomgen generate ${model} -o ${output} ${defines}
    DEPENDS ${model} eomgen::eomgen
    COMMENT "eomgen: generating ${stem}.hpp from ${ARG_MODEL}"
    VERBATIM)
  add_custom_target(${ARG_TARGET}_generate DEPENDS ${output})
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_generate)
  target_include_directories(${ARG_TARGET} INTERFACE ${output_dir})
  target_link_libraries(${ARG_TARGET} INTERFACE Eigen3::Eigen)
  if(ARG_LINEARIZATION)
    target_link_libraries(${ARG_TARGET} INTERFACE eomgen::runtime)
  endif()
endfunction()
