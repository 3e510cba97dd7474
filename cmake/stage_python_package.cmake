# Stages the Python package for a plain build (ctest, the scripts): copies SOURCE (python/pamkit)
# onto STAGED (<build>/python/pamkit) and removes what SOURCE no longer has, so that a module or a
# subpackage renamed or deleted in the sources cannot still be imported from the build. The
# compiled extension, which the build writes into STAGED, stays.
#   cmake -DSOURCE=... -DSTAGED=... -P stage_python_package.cmake
file(GLOB_RECURSE staged_paths LIST_DIRECTORIES true RELATIVE ${STAGED} ${STAGED}/*)
foreach(path IN LISTS staged_paths)
  get_filename_component(name ${path} NAME)
  if(EXISTS ${STAGED}/${path} AND NOT EXISTS ${SOURCE}/${path} AND NOT name STREQUAL "__pycache__"
     AND NOT path MATCHES "(^|/)__pycache__/" AND NOT name MATCHES "^_core[.].*[.](so|pyd)$")
    file(REMOVE_RECURSE ${STAGED}/${path})
  endif()
endforeach()
file(COPY ${SOURCE}/ DESTINATION ${STAGED})
