# Firmware variants for bench_logger.py's rate sweep: no oversampling (the fastest the sketch can
# sample both channels), at 115200 and at 1 Mbaud. Not built by default:
#   cmake --build build --target bench_logger_firmware
set(bench_firmware_targets)
foreach(rate 200 400 500 550 600 625 650 700 800)
  pamkit_add_firmware(bench_115200_${rate}hz RATE_HZ ${rate} OVERSAMPLE 1 BAUD 115200)
  list(APPEND bench_firmware_targets firmware_bench_115200_${rate}hz)
endforeach()
foreach(rate 1000 1250 1500 1600 1700 1750 1800 2000)
  pamkit_add_firmware(bench_1000000_${rate}hz RATE_HZ ${rate} OVERSAMPLE 1 BAUD 1000000)
  list(APPEND bench_firmware_targets firmware_bench_1000000_${rate}hz)
endforeach()
# the shipped oversampling (16x) at 115200: its ceiling is the ADC, not the line
foreach(rate 100 200 250)
  pamkit_add_firmware(bench_115200_${rate}hz_16x RATE_HZ ${rate} OVERSAMPLE 16 BAUD 115200)
  list(APPEND bench_firmware_targets firmware_bench_115200_${rate}hz_16x)
endforeach()
add_custom_target(bench_logger_firmware DEPENDS ${bench_firmware_targets})
