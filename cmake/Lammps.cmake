# Which LAMMPS tylmp builds against, its full source headers, and its version.
#
# Two ways, chosen by LAMMPS_SOURCE_DIR:
#  * empty (default): the installed Debian package (liblammps-dev: LAMMPS::lammps); the internal
#    headers it does not ship are fetched from the Debian source package of exactly that version
#    (cmake/LammpsSourceHeaders.cmake), as on Debian 12 (29 Sep 2021) and Debian 13 (4 Feb 2025).
#  * a LAMMPS source tree (the directory holding src/): its headers; LAMMPS::lammps is linked too
#    when find_package(LAMMPS) finds an installed build of the same version (a source build's
#    prefix on CMAKE_PREFIX_PATH), else the library resolves LAMMPS symbols from the lmp that
#    loads it (a static lmp built with PLUGIN exports them).
#
# Results: LAMMPS_SOURCE_INCLUDE_DIRS, TYLMP_LAMMPS_VERSION (YYYYMMDD of the headers' version.h,
# the key of plugin/lammps/lammps_compat.h), TYLMP_LAMMPS_LINK (LAMMPS::lammps or empty).

set(LAMMPS_SOURCE_DIR "" CACHE PATH
  "LAMMPS source tree (with src/) to build against; empty: the installed Debian package")

# "4 Feb 2025" (src/version.h) -> 20250204
function(tylmp_lammps_header_version src_dir out_var)
  file(STRINGS "${src_dir}/version.h" _line REGEX "#define LAMMPS_VERSION ")
  if(NOT _line MATCHES "\"([0-9]+) ([A-Za-z]+) ([0-9]+)\"")
    message(FATAL_ERROR "tylmp: cannot read the LAMMPS version from ${src_dir}/version.h")
  endif()
  set(_day "${CMAKE_MATCH_1}")
  set(_year "${CMAKE_MATCH_3}")
  set(_months Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec)
  list(FIND _months "${CMAKE_MATCH_2}" _m)
  if(_m LESS 0)
    message(FATAL_ERROR "tylmp: unknown month in ${src_dir}/version.h: ${_line}")
  endif()
  math(EXPR _num "${_year} * 10000 + (${_m} + 1) * 100 + ${_day}")
  set(${out_var} "${_num}" PARENT_SCOPE)
endfunction()

if(LAMMPS_SOURCE_DIR)
  get_filename_component(LAMMPS_SOURCE_DIR "${LAMMPS_SOURCE_DIR}" ABSOLUTE)
  set(_hdr_root "${LAMMPS_SOURCE_DIR}/src")
  if(NOT EXISTS "${_hdr_root}/version.h" OR NOT EXISTS "${_hdr_root}/fix_neigh_history.h")
    message(FATAL_ERROR "tylmp: LAMMPS_SOURCE_DIR=${LAMMPS_SOURCE_DIR} is not a LAMMPS source "
      "tree (no src/version.h and src/fix_neigh_history.h)")
  endif()
  set(LAMMPS_SOURCE_INCLUDE_DIRS "${_hdr_root}" "${_hdr_root}/GRANULAR")
  tylmp_lammps_header_version("${_hdr_root}" TYLMP_LAMMPS_VERSION)
  find_package(LAMMPS QUIET CONFIG)
  set(TYLMP_LAMMPS_LINK "")
  if(LAMMPS_FOUND AND LAMMPS_VERSION STREQUAL TYLMP_LAMMPS_VERSION)
    set(TYLMP_LAMMPS_LINK LAMMPS::lammps)
    message(STATUS "tylmp: linking the installed LAMMPS ${LAMMPS_VERSION} (${LAMMPS_DIR})")
  elseif(LAMMPS_FOUND)
    message(STATUS "tylmp: the installed LAMMPS ${LAMMPS_VERSION} (${LAMMPS_DIR}) is not the "
      "version of LAMMPS_SOURCE_DIR (${TYLMP_LAMMPS_VERSION}): not linked; the symbols come "
      "from the lmp that loads the library")
  endif()
else()
  find_package(LAMMPS CONFIG)
  if(NOT LAMMPS_FOUND)
    message(FATAL_ERROR "tylmp: no installed LAMMPS found (Debian: apt-get install lammps "
      "liblammps-dev python3-lammps), or give a source tree with -DLAMMPS_SOURCE_DIR=...")
  endif()
  include(${CMAKE_CURRENT_LIST_DIR}/LammpsSourceHeaders.cmake)
  tylmp_lammps_header_version("${_hdr_root}" TYLMP_LAMMPS_VERSION)
  if(NOT LAMMPS_VERSION STREQUAL TYLMP_LAMMPS_VERSION)
    message(FATAL_ERROR "tylmp: the installed LAMMPS is ${LAMMPS_VERSION} but the fetched "
      "headers (${_hdr_root}) are ${TYLMP_LAMMPS_VERSION}: delete ${TYLMP_HEADER_CACHE}")
  endif()
  set(TYLMP_LAMMPS_LINK LAMMPS::lammps)
endif()
message(STATUS "tylmp: building against LAMMPS ${TYLMP_LAMMPS_VERSION}")
