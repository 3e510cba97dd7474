# Finds libserialport (Debian: libserialport-dev) and defines LibSerialPort::LibSerialPort.
# Installed next to pamkitConfig.cmake so that find_package(pamkit) finds it again.
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(PC_LIBSERIALPORT QUIET libserialport)
endif()
find_path(LibSerialPort_INCLUDE_DIR libserialport.h HINTS ${PC_LIBSERIALPORT_INCLUDE_DIRS})
find_library(LibSerialPort_LIBRARY NAMES serialport HINTS ${PC_LIBSERIALPORT_LIBRARY_DIRS})
set(LibSerialPort_VERSION ${PC_LIBSERIALPORT_VERSION})
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LibSerialPort
  REQUIRED_VARS LibSerialPort_LIBRARY LibSerialPort_INCLUDE_DIR VERSION_VAR LibSerialPort_VERSION)
if(LibSerialPort_FOUND AND NOT TARGET LibSerialPort::LibSerialPort)
  add_library(LibSerialPort::LibSerialPort UNKNOWN IMPORTED)
  set_target_properties(LibSerialPort::LibSerialPort PROPERTIES
    IMPORTED_LOCATION ${LibSerialPort_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${LibSerialPort_INCLUDE_DIR})
endif()
mark_as_advanced(LibSerialPort_INCLUDE_DIR LibSerialPort_LIBRARY)
