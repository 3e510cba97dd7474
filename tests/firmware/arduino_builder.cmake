# Builds the sketch folder as the Arduino IDE (1.6.6-1.8.x) does, with arduino-builder: the
# .ino preprocessing (prototypes, #include <Arduino.h>), the sketch folder copied to a temporary
# build tree, its tabs (pamkit_frame.h) found there. Passes if it compiles and links, with no
# warning (-warnings all) in the sketch's own files. Debian's core needs
# -DDECIMAL_DIG=__DECIMAL_DIG__ with gcc-avr 5.4 (the IDE's bundled toolchain does not).
# Arguments: BUILDER, CORE_DIR (…/hardware/arduino/avr), SKETCH (the .ino), WORK (scratch dir).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/hardware ${WORK}/build)
# arduino-builder wants a hardware folder with the ctags recipe (Debian ships it separately)
file(COPY /usr/share/arduino-builder/platform.txt DESTINATION ${WORK}/hardware)
get_filename_component(vendor_dir ${CORE_DIR} DIRECTORY)
file(CREATE_LINK ${vendor_dir} ${WORK}/hardware/arduino SYMBOLIC)
execute_process(
  COMMAND ${BUILDER} -hardware ${WORK}/hardware -tools /usr/bin -fqbn arduino:avr:mega:cpu=atmega2560
          -build-path ${WORK}/build -ide-version 10807 -warnings all
          -prefs "compiler.c.extra_flags=-DDECIMAL_DIG=__DECIMAL_DIG__"
          -prefs "compiler.cpp.extra_flags=-DDECIMAL_DIG=__DECIMAL_DIG__" ${SKETCH}
  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "arduino-builder failed (${status}):\n${out}\n${err}")
endif()
string(REGEX MATCHALL "[^\n]*(pamkit_logger\\.ino|pamkit_frame\\.h)[^\n]*warning[^\n]*" sketch_warnings "${out}\n${err}")
if(sketch_warnings)
  message(FATAL_ERROR "warnings in the sketch:\n${sketch_warnings}")
endif()
string(REGEX MATCHALL "(Sketch uses|Global variables use)[^\n]*" sizes "${out}")
message("${sizes}")
