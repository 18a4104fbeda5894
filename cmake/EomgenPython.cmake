# eomgen_add_python_module(TARGET name MODEL file.eom [MODULE_NAME name] [DEFINE n=8 ...]
#                          [OUTPUT_DIRECTORY dir])
#
# Builds the Python module of a model at build time: `eomgen python --source-only` writes the
# model's header (with linearization_terms) and its binding source, and pybind11 compiles them
# into MODULE_NAME<extension suffix> (MODULE_NAME defaults to the model file's stem) in
# OUTPUT_DIRECTORY (default: the current binary directory), so that `import MODULE_NAME` works
# with that directory on sys.path. Both are rewritten when the model file or eomgen changes.
# Needs pybind11 (find_package(pybind11 CONFIG)) and the eompy library (eomgen::python).
function(eomgen_add_python_module)
  cmake_parse_arguments(ARG "" "TARGET;MODEL;MODULE_NAME;OUTPUT_DIRECTORY" "DEFINE" ${ARGN})
  if(NOT ARG_TARGET OR NOT ARG_MODEL)
    message(FATAL_ERROR "eomgen_add_python_module: TARGET and MODEL are required")
  endif()
  if(NOT COMMAND pybind11_add_module)
    message(FATAL_ERROR "eomgen_add_python_module: needs pybind11: find_package(pybind11 CONFIG REQUIRED) first")
  endif()
  get_filename_component(model ${ARG_MODEL} ABSOLUTE)
  if(NOT ARG_MODULE_NAME)
    get_filename_component(ARG_MODULE_NAME ${ARG_MODEL} NAME_WE)
  endif()
  if(NOT ARG_OUTPUT_DIRECTORY)
    set(ARG_OUTPUT_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  endif()
  set(source_dir ${CMAKE_CURRENT_BINARY_DIR}/eomgen_python/${ARG_TARGET})
  set(defines)
  foreach(definition IN LISTS ARG_DEFINE)
    list(APPEND defines --define ${definition})
  endforeach()
  add_custom_command(
    OUTPUT ${source_dir}/model.hpp ${source_dir}/module.cpp
    COMMAND eomgen::eomgen python ${model} --source-only -o ${source_dir} --module-name ${ARG_MODULE_NAME} ${defines}
    DEPENDS ${model} eomgen::eomgen
    COMMENT "eomgen: writing the Python module ${ARG_MODULE_NAME} of ${ARG_MODEL}"
    VERBATIM)
  pybind11_add_module(${ARG_TARGET} MODULE ${source_dir}/module.cpp)
  target_include_directories(${ARG_TARGET} PRIVATE ${source_dir})
  target_link_libraries(${ARG_TARGET} PRIVATE eomgen::python)
  set_target_properties(${ARG_TARGET} PROPERTIES
    OUTPUT_NAME ${ARG_MODULE_NAME}
    LIBRARY_OUTPUT_DIRECTORY ${ARG_OUTPUT_DIRECTORY})
endfunction()
