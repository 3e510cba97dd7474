// pamkit logger for the Arduino Mega 2560: samples the pressure transducer on A0 and the TMP36
// on A1 at a fixed rate and streams binary frames (pamkit_frame.h) to the USB serial port.
//
// Thesis appendix B: a 61CP ceramic pressure transducer and a TMP36 inside the muscle, both read
// by an Arduino Mega 2560. Wiring, calibration and flashing: ../README.md.
//
// Opens unchanged in the Arduino IDE (Board: "Arduino Mega or Mega 2560"). The settings below can
// be edited here or overridden with -D from the CMake build (firmware/CMakeLists.txt).

#include <stdio.h>

#include "pamkit_frame.h"

// ---- settings ----------------------------------------------------------------------------
#ifndef PAMKIT_SAMPLE_RATE_HZ
#define PAMKIT_SAMPLE_RATE_HZ 100UL  // samples per second, both channels
#endif
#ifndef PAMKIT_OVERSAMPLE
#define PAMKIT_OVERSAMPLE 16  // conversions summed per channel and sample (1..64)
#endif
#ifndef PAMKIT_BAUD
#define PAMKIT_BAUD 115200UL  // 115200 or 1000000 (exact at 16 MHz with U2X)
#endif
#ifndef PAMKIT_VREF_MV
#define PAMKIT_VREF_MV 5000U  // analogReference(DEFAULT) is AVCC on the Mega: measure it, see README
#endif
// -------------------------------------------------------------------------------------------

// One analogRead takes 13 ADC clocks at 16 MHz / 128 = 104 us, about 112 us with its overhead.
static const unsigned long kConversionUs = 112UL;
static const unsigned long kPeriodUs = (1000000UL + PAMKIT_SAMPLE_RATE_HZ / 2) / PAMKIT_SAMPLE_RATE_HZ;

static_assert(PAMKIT_SAMPLE_RATE_HZ >= 1 && PAMKIT_SAMPLE_RATE_HZ <= 10000UL,
              "PAMKIT_SAMPLE_RATE_HZ must be within 1..10000");
static_assert(PAMKIT_OVERSAMPLE >= 1 && PAMKIT_OVERSAMPLE <= PAMKIT_OVERSAMPLE_MAX,
              "PAMKIT_OVERSAMPLE must be within 1..64 (the sums are 16-bit)");
static_assert(2UL * PAMKIT_OVERSAMPLE * kConversionUs < kPeriodUs,
              "the conversions of one sample do not fit in the sample period: "
              "lower PAMKIT_OVERSAMPLE or PAMKIT_SAMPLE_RATE_HZ");

static uint16_t g_seq = 0;           // number of the next sample
static unsigned long g_next_us = 0;  // when the next sample is due (micros())
static uint8_t g_dropped = 0;        // samples lost since the last frame sent

static void count_dropped(unsigned long samples) {
  const unsigned long total = g_dropped + samples;
  g_dropped = total > 255UL ? 255 : (uint8_t)total;
}

// Sum of PAMKIT_OVERSAMPLE conversions of one input. The transducer and the TMP36 both have
// low output impedance, so the first conversion after switching the multiplexer is kept.
static uint16_t read_sum(uint8_t pin) {
  uint16_t sum = 0;
  for (uint8_t i = 0; i < PAMKIT_OVERSAMPLE; ++i) sum += (uint16_t)analogRead(pin);
  return sum;
}

static void send_banner() {
  char line[PAMKIT_BANNER_MAX];
  int length = snprintf(line, sizeof line, PAMKIT_BANNER_FORMAT, PAMKIT_FIRMWARE_VERSION,
                        (unsigned)PAMKIT_FRAME_VERSION, (unsigned long)PAMKIT_SAMPLE_RATE_HZ, kPeriodUs,
                        (unsigned)PAMKIT_OVERSAMPLE, (unsigned long)PAMKIT_BAUD, (unsigned)PAMKIT_VREF_MV);
  const uint16_t crc = pamkit_crc16((const uint8_t*)line, (size_t)length);
  snprintf(line + length, sizeof line - (size_t)length, " crc=%04X\r\n", crc);
  Serial.print(line);
  Serial.flush();
}

void setup() {
  Serial.begin(PAMKIT_BAUD);
  analogReference(DEFAULT);
  send_banner();
  g_next_us = micros();
}

void loop() {
  const unsigned long now = micros();
  if ((long)(now - g_next_us) < 0) return;  // not due yet

  // Later than a whole period: those samples are lost. Skip them (the sequence number jumps)
  // and say so in the next frame, so the host can tell them from bytes lost on the cable.
  const unsigned long late = now - g_next_us;
  if (late >= kPeriodUs) {
    const unsigned long missed = late / kPeriodUs;
    g_seq = (uint16_t)(g_seq + missed);
    g_next_us += missed * kPeriodUs;
    count_dropped(missed);
  }
  g_next_us += kPeriodUs;

  pamkit_frame frame;
  frame.seq = g_seq++;
  frame.time_us = now;
  frame.counts[PAMKIT_CHANNEL_PRESSURE] = read_sum(A0);
  frame.counts[PAMKIT_CHANNEL_TEMPERATURE] = read_sum(A1);
  frame.oversample = PAMKIT_OVERSAMPLE;
  frame.dropped = g_dropped;

  uint8_t bytes[PAMKIT_FRAME_SIZE];
  pamkit_frame_encode(&frame, bytes);
  // Never block on a full serial buffer: a late sample is worse than a missing one, which the
  // next frame reports.
  if (Serial.availableForWrite() >= PAMKIT_FRAME_SIZE) {
    Serial.write(bytes, PAMKIT_FRAME_SIZE);
    g_dropped = 0;
  } else {
    count_dropped(1);
  }
}
