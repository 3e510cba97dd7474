# What pamkit needs from the system that pip cannot install, checked before anything else so that
# `pip install .` (or a plain configure) on a machine without them stops with one message naming
# every missing piece and the package that provides it, instead of the first find_package's wall
# of text. Included by the top CMakeLists.txt after project(... LANGUAGES NONE) and before
# enable_language(); the real find_package calls that follow stay REQUIRED.
#
# The libraries are checked by their headers (what their -dev packages install), which needs no
# compiler, so that a machine missing the compiler too hears about everything at once. Only what
# the parts switched on need is checked (CMakeLists.txt's PAMKIT_BUILD_* options): Boost alone for
# PAMKIT_BUILD_LIBRARY=OFF.

include(CheckLanguage)
set(pamkit_missing)

# CMake caches a compiler it did not find as NOTFOUND and would not look again.
foreach(language C CXX)
  if(DEFINED CMAKE_${language}_COMPILER AND NOT CMAKE_${language}_COMPILER)
    unset(CMAKE_${language}_COMPILER CACHE)
  endif()
  check_language(${language})
endforeach()
if(NOT CMAKE_C_COMPILER OR NOT CMAKE_CXX_COMPILER)
  list(APPEND pamkit_missing
    "a C and C++17 compiler    Debian: build-essential   Homebrew: xcode-select --install   conda: c-compiler cxx-compiler")
endif()

# Where Homebrew and conda put headers, besides CMake's usual prefixes (/usr, /usr/local, CMAKE_PREFIX_PATH).
set(pamkit_check_hints $ENV{CONDA_PREFIX} $ENV{HOMEBREW_PREFIX} /opt/homebrew)

find_path(PAMKIT_CHECK_BOOST_INCLUDE_DIR boost/version.hpp HINTS ${pamkit_check_hints} PATH_SUFFIXES include)
if(PAMKIT_CHECK_BOOST_INCLUDE_DIR)
  file(STRINGS ${PAMKIT_CHECK_BOOST_INCLUDE_DIR}/boost/version.hpp pamkit_check_boost_version REGEX "^#define BOOST_VERSION [0-9]+")
  string(REGEX REPLACE ".* ([0-9]+)$" "\\1" pamkit_check_boost_version "${pamkit_check_boost_version}")
endif()
if(NOT PAMKIT_CHECK_BOOST_INCLUDE_DIR OR pamkit_check_boost_version LESS 107100)
  list(APPEND pamkit_missing
    "Boost >= 1.71 (headers)   Debian: libboost-dev      Homebrew: boost                    conda: libboost-headers")
endif()

if(PAMKIT_BUILD_LIBRARY)
  find_path(PAMKIT_CHECK_SUNDIALS_INCLUDE_DIR sundials/sundials_config.h HINTS ${pamkit_check_hints} PATH_SUFFIXES include)
  if(PAMKIT_CHECK_SUNDIALS_INCLUDE_DIR AND EXISTS ${PAMKIT_CHECK_SUNDIALS_INCLUDE_DIR}/cvodes/cvodes.h)
    file(STRINGS ${PAMKIT_CHECK_SUNDIALS_INCLUDE_DIR}/sundials/sundials_config.h pamkit_check_sundials_major
         REGEX "^#define SUNDIALS_VERSION_MAJOR [0-9]+")
    string(REGEX REPLACE ".* ([0-9]+)$" "\\1" pamkit_check_sundials_major "${pamkit_check_sundials_major}")
  endif()
  if(NOT pamkit_check_sundials_major OR pamkit_check_sundials_major LESS 6 OR pamkit_check_sundials_major GREATER 7)
    list(APPEND pamkit_missing
      "SUNDIALS 6 or 7 (CVODES)  Debian: libsundials-dev   Homebrew: sundials                 conda: sundials")
  endif()
endif()

if(PAMKIT_BUILD_PYTHON OR PAMKIT_BUILD_TESTS)  # they compile the muscle-parameters file's reader
  find_path(PAMKIT_CHECK_TOMLPLUSPLUS_INCLUDE_DIR toml++/toml.h HINTS ${pamkit_check_hints} PATH_SUFFIXES include)
  if(NOT PAMKIT_CHECK_TOMLPLUSPLUS_INCLUDE_DIR)
    list(APPEND pamkit_missing
      "toml++ 3 (headers)        Debian: libtomlplusplus-dev Homebrew: tomlplusplus           conda: tomlplusplus")
  endif()
endif()

if(PAMKIT_BUILD_LOGGER)
  find_path(PAMKIT_CHECK_SERIALPORT_INCLUDE_DIR libserialport.h HINTS ${pamkit_check_hints} PATH_SUFFIXES include)
  if(NOT PAMKIT_CHECK_SERIALPORT_INCLUDE_DIR)
    list(APPEND pamkit_missing
      "libserialport (headers)   Debian: libserialport-dev Homebrew: libserialport            conda: libserialport")
  endif()
endif()

# The extension compiles against the headers of the Python that builds it (pip's, or the one
# given as Python_EXECUTABLE); Debian's own Python ships them separately.
if(PAMKIT_BUILD_PYTHON)
  if(DEFINED Python_EXECUTABLE)
    set(pamkit_check_python ${Python_EXECUTABLE})
  else()
    find_program(pamkit_check_python NAMES python3 python)
  endif()
  if(pamkit_check_python)
    execute_process(COMMAND ${pamkit_check_python} -c "import sysconfig; print(sysconfig.get_paths()['include'])"
      OUTPUT_VARIABLE pamkit_check_python_include OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  endif()
  if(NOT pamkit_check_python_include OR NOT EXISTS "${pamkit_check_python_include}/Python.h")
    list(APPEND pamkit_missing
      "Python 3 headers          Debian: python3-dev       (Homebrew's and conda's Python include them)")
  endif()
endif()
mark_as_advanced(PAMKIT_CHECK_BOOST_INCLUDE_DIR PAMKIT_CHECK_SUNDIALS_INCLUDE_DIR PAMKIT_CHECK_SERIALPORT_INCLUDE_DIR
                 PAMKIT_CHECK_TOMLPLUSPLUS_INCLUDE_DIR)

if(pamkit_missing)
  list(JOIN pamkit_missing "\n  - " pamkit_check_missing_lines)
  message(FATAL_ERROR
    "pamkit cannot be built: the system lacks what pip cannot install.\n"
    "Missing:\n  - ${pamkit_check_missing_lines}\n"
    "On Debian 12, scripts/install-deps.sh installs all of them (apt-get install build-essential "
    "libboost-dev libsundials-dev libserialport-dev libtomlplusplus-dev python3-dev). If they are installed in an unusual "
    "place, give it with -DCMAKE_PREFIX_PATH=... (pip: --config-settings=cmake.define.CMAKE_PREFIX_PATH=...).")
endif()
