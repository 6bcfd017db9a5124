# Obtain the internal LAMMPS headers that Debian's liblammps-dev does not ship
# (neigh_request.h, fix_neigh_history.h, fmt/, ...) from the Debian source package
# of exactly the installed LAMMPS version. The extracted headers are cached per version.
#
# Result: LAMMPS_SOURCE_INCLUDE_DIRS (src/ and src/GRANULAR of that version).

# (liblammps-dev, which holds LAMMPSConfig.cmake: Debian 13 renamed liblammps0 liblammps0t64)
execute_process(
  COMMAND dpkg-query -W [=[-f=${source:Version}]=] liblammps-dev
  OUTPUT_VARIABLE _lmp_src_version RESULT_VARIABLE _rc ERROR_QUIET)
if(NOT _rc EQUAL 0 OR _lmp_src_version STREQUAL "")
  message(FATAL_ERROR "tylmp: cannot find the Debian package liblammps-dev "
    "(apt-get install lammps liblammps-dev python3-lammps)")
endif()

set(TYLMP_HEADER_CACHE "$ENV{HOME}/.cache/tylmp/lammps-${_lmp_src_version}"
  CACHE PATH "where the LAMMPS source headers of the installed version are kept")
set(_hdr_root "${TYLMP_HEADER_CACHE}/src")

if(NOT EXISTS "${_hdr_root}/neigh_request.h" OR NOT EXISTS "${_hdr_root}/fmt/format.h")
  set(_dl "${TYLMP_HEADER_CACHE}/download")
  file(MAKE_DIRECTORY "${_dl}")
  file(GLOB _orig "${_dl}/lammps_*.orig.tar.*")
  if(NOT _orig)
    message(STATUS "tylmp: fetching Debian source of lammps ${_lmp_src_version}")
    execute_process(
      COMMAND apt-get source --download-only "lammps=${_lmp_src_version}"
      WORKING_DIRECTORY "${_dl}" RESULT_VARIABLE _rc OUTPUT_QUIET ERROR_VARIABLE _err)
    file(GLOB _orig "${_dl}/lammps_*.orig.tar.*")
    if(NOT _rc EQUAL 0 OR NOT _orig)
      message(FATAL_ERROR "tylmp: 'apt-get source --download-only lammps=${_lmp_src_version}' "
        "failed:\n${_err}\nAdd a deb-src entry for this Debian release (scripts/setup.sh "
        "does it) and run 'apt-get update'.")
    endif()
  endif()
  list(GET _orig 0 _orig)
  set(_tmp "${TYLMP_HEADER_CACHE}/extract")
  file(REMOVE_RECURSE "${_tmp}")
  file(MAKE_DIRECTORY "${_tmp}")
  execute_process(
    COMMAND tar -xf "${_orig}" --wildcards --no-wildcards-match-slash
      "*/src/*.h" "*/src/fmt/*" "*/src/GRANULAR/*.h"
    WORKING_DIRECTORY "${_tmp}" RESULT_VARIABLE _rc ERROR_VARIABLE _err)
  file(GLOB _top "${_tmp}/*")
  if(NOT _rc EQUAL 0 OR NOT EXISTS "${_top}/src/neigh_request.h")
    message(FATAL_ERROR "tylmp: extracting headers from ${_orig} failed:\n${_err}")
  endif()
  file(REMOVE_RECURSE "${_hdr_root}")
  file(RENAME "${_top}/src" "${_hdr_root}")
  file(REMOVE_RECURSE "${_tmp}")
endif()

set(LAMMPS_SOURCE_INCLUDE_DIRS "${_hdr_root}" "${_hdr_root}/GRANULAR")
message(STATUS "tylmp: LAMMPS ${_lmp_src_version} headers in ${_hdr_root}")
