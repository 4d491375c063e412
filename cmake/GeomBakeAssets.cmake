# GeomBakeAssets.cmake: geombake as a build step (docs/build-step.md), for
# projects that find the installed package (find_package(geom) includes this
# file) or build geom in their tree.
#
#   geom_bake_assets(TARGET FILES...
#                    [OUTPUT_DIR dir]     # default: ${CMAKE_CURRENT_BINARY_DIR}/baked
#                    [OPTIONS flags...])  # geombake bake flags (--no-esm, --light X,Y,Z,W, ...)
#
# Bakes each file to OUTPUT_DIR/<path>.gbake, where <path> is the file's path
# relative to CMAKE_CURRENT_SOURCE_DIR (its base name if outside it), with one
# geombake run per file, and adds the custom target TARGET (built by ALL) that
# bakes them. The outputs are exposed to the caller's targets in the variable
# TARGET_OUTPUTS and the target property GEOM_BAKED_FILES (depend on them in
# add_custom_command, or add_dependencies on TARGET).
#
# The same behaviour with Ninja and with Makefile generators: a no-op rebuild
# runs nothing; a touched input is rebaked once, and not again on the next
# build; a changed file an input reads (a glTF's external .bin) rebakes it; a
# failed bake fails the build and is retried by the next one. How: geombake
# leaves an output whose bytes did not change untouched (its mtime kept, so
# Ninja's restat skips what depends on it), which a timestamp-only tool like
# Make would take as out of date forever; so each bake also touches a stamp
# file, the rule's main output, and writes its depfile for that stamp
# (--depfile-target), which both generators read (DEPFILE).
#
# GEOMBAKE_EXECUTABLE (cache) names the geombake to run; by default the
# installed one beside this package (or the geombake target of this build).
cmake_minimum_required(VERSION 3.21)  # DEPFILE with Makefile generators

if(NOT TARGET geom::geombake)
  if(TARGET geombake)
    add_executable(geom::geombake ALIAS geombake)
  else()
    # <prefix>/<libdir>/cmake/geom: the prefix is the folder above with bin/geombake.
    set(_geom_dir "${CMAKE_CURRENT_LIST_DIR}")
    set(_geom_hints "")
    foreach(_geom_up RANGE 1 4)
      get_filename_component(_geom_dir "${_geom_dir}" DIRECTORY)
      list(APPEND _geom_hints "${_geom_dir}/bin")
    endforeach()
    find_program(GEOMBAKE_EXECUTABLE geombake HINTS ${_geom_hints} NO_DEFAULT_PATH)
    find_program(GEOMBAKE_EXECUTABLE geombake)
    if(GEOMBAKE_EXECUTABLE)
      add_executable(geom::geombake IMPORTED GLOBAL)
      set_target_properties(geom::geombake PROPERTIES IMPORTED_LOCATION "${GEOMBAKE_EXECUTABLE}")
    endif()
    unset(_geom_dir)
    unset(_geom_hints)
    unset(_geom_up)
  endif()
endif()

function(geom_bake_assets target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "OUTPUT_DIR" "FILES;OPTIONS")
  set(files ${arg_FILES} ${arg_UNPARSED_ARGUMENTS})
  if(NOT files)
    message(FATAL_ERROR "geom_bake_assets(${target}): no FILES to bake")
  endif()
  if(NOT TARGET geom::geombake)
    message(FATAL_ERROR "geom_bake_assets(${target}): geombake not found (set GEOMBAKE_EXECUTABLE)")
  endif()
  set(out_dir "${arg_OUTPUT_DIR}")
  if(NOT out_dir)
    set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/baked")
  endif()
  get_filename_component(out_dir "${out_dir}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  set(stamp_dir "${CMAKE_CURRENT_BINARY_DIR}/CMakeFiles/${target}.geombake")
  set(outputs "")
  set(stamps "")
  foreach(file IN LISTS files)
    get_filename_component(input "${file}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    file(RELATIVE_PATH rel "${CMAKE_CURRENT_SOURCE_DIR}" "${input}")
    if(rel MATCHES "^\\.\\./" OR IS_ABSOLUTE "${rel}")
      get_filename_component(rel "${input}" NAME)
    endif()
    set(output "${out_dir}/${rel}.gbake")
    set(stamp "${stamp_dir}/${rel}.stamp")
    get_filename_component(output_folder "${output}" DIRECTORY)
    get_filename_component(stamp_folder "${stamp}" DIRECTORY)
    file(MAKE_DIRECTORY "${output_folder}" "${stamp_folder}")
    add_custom_command(
      OUTPUT "${stamp}"
      BYPRODUCTS "${output}"
      COMMAND geom::geombake bake -q ${arg_OPTIONS} "${input}" -o "${output}" --depfile "${stamp}.d"
              --depfile-target "${stamp}"
      COMMAND "${CMAKE_COMMAND}" -E touch "${stamp}"
      DEPENDS "${input}" geom::geombake
      DEPFILE "${stamp}.d"
      COMMENT "Baking ${rel}"
      VERBATIM)
    list(APPEND outputs "${output}")
    list(APPEND stamps "${stamp}")
  endforeach()
  add_custom_target(${target} ALL DEPENDS ${stamps})
  set_target_properties(${target} PROPERTIES GEOM_BAKED_FILES "${outputs}")
  set(${target}_OUTPUTS "${outputs}" PARENT_SCOPE)
endfunction()
