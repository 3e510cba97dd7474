/* pamkit_frame.h - the pamkit logger's wire format, defined once.
 *
 * Included unchanged by the Arduino sketch (pamkit_logger.ino, avr-gcc, C++11), by the host
 * decoder (include/pamkit/logger/decoder.hpp, C++17) and by the simavr test harness (C99).
 * It therefore stays plain C: no exceptions, no iostreams, no allocation, no globals.
 *
 * The stream from the board is
 *   - one banner line at start-up (ASCII, PAMKIT_BANNER_FORMAT, ended by " crc=XXXX\r\n"),
 *   - then one binary frame of PAMKIT_FRAME_SIZE bytes per sample:
 *
 *     offset size  field
 *      0     1     sync byte 0xA5
 *      1     1     sync byte 0x5A
 *      2     2     seq          sample number since reset, wraps at 65536
 *      4     4     time_us      device time at the start of the sample, micros(), wraps at 2^32
 *      8     2     counts[0]    A0 (pressure transducer): sum of `oversample` 10-bit conversions
 *     10     2     counts[1]    A1 (TMP36): sum of `oversample` 10-bit conversions
 *     12     1     oversample   conversions summed per channel (1..64)
 *     13     1     dropped      samples the board lost since the previous frame it sent
 *                               (serial buffer full or loop late; saturates at 255)
 *     14     2     crc          CRC-16/CCITT-FALSE of bytes 2..13
 *
 *   Multi-byte fields are little-endian. The banner is 7-bit ASCII, so it can never contain a
 *   sync byte; a frame can, which is why the decoder checks the CRC before trusting one.
 */
#ifndef PAMKIT_FRAME_H
#define PAMKIT_FRAME_H

#include <stddef.h>
#include <stdint.h>

#define PAMKIT_FIRMWARE_VERSION "1.0.0"
#define PAMKIT_FRAME_VERSION 1

#define PAMKIT_FRAME_SYNC0 0xA5
#define PAMKIT_FRAME_SYNC1 0x5A
#define PAMKIT_FRAME_SIZE 16
#define PAMKIT_FRAME_CRC_OFFSET 14
#define PAMKIT_CHANNELS 2
#define PAMKIT_CHANNEL_PRESSURE 0    /* A0: 61CP pressure transducer (thesis appendix B) */
#define PAMKIT_CHANNEL_TEMPERATURE 1 /* A1: TMP36 inside the muscle (thesis appendix B) */
#define PAMKIT_OVERSAMPLE_MAX 64     /* 64 x 1023 = 65472 still fits a uint16_t sum */
#define PAMKIT_ADC_FULL_SCALE 1024   /* ATmega2560 datasheet: ADC = Vin * 1024 / Vref */

/* The banner: one line, every value a decimal number except version and board. The line ends
 * with " crc=" and the CRC-16 (4 upper-case hex digits) of everything before that space. */
#define PAMKIT_BANNER_TAG "#pamkit-logger"
#define PAMKIT_BANNER_FORMAT                                      \
  PAMKIT_BANNER_TAG                                               \
  " version=%s frame=%u board=mega2560 rate_hz=%lu period_us=%lu" \
  " oversample=%u baud=%lu vref_mV=%u a0=pressure a1=tmp36"
#define PAMKIT_BANNER_MAX 192 /* longest banner line a decoder must accept, "\r\n" included */

/** One decoded sample, in the board's raw units. */
typedef struct pamkit_frame {
  uint16_t seq;                     /**< sample number since reset (wraps at 65536) */
  uint32_t time_us;                 /**< device time at the start of the sample [us], wraps */
  uint16_t counts[PAMKIT_CHANNELS]; /**< sums of `oversample` 10-bit conversions [counts] */
  uint8_t oversample;               /**< conversions per channel in the sums (1..64) */
  uint8_t dropped;                  /**< samples lost on the board since the previous frame */
} pamkit_frame;

/** CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF), one byte at a time without a table
 *  (cheap on the AVR: no 512-byte table in flash). Check value: "123456789" -> 0x29B1. */
static inline uint16_t pamkit_crc16_update(uint16_t crc, uint8_t byte) {
  crc = (uint16_t)((crc >> 8) | (crc << 8));
  crc ^= byte;
  crc ^= (uint16_t)((crc & 0xFFu) >> 4);
  crc ^= (uint16_t)(crc << 12);
  crc ^= (uint16_t)((crc & 0xFFu) << 5);
  return crc;
}

/** CRC-16/CCITT-FALSE of `size` bytes. */
static inline uint16_t pamkit_crc16(const uint8_t* data, size_t size) {
  uint16_t crc = 0xFFFFu;
  size_t i;
  for (i = 0; i < size; ++i) crc = pamkit_crc16_update(crc, data[i]);
  return crc;
}

static inline void pamkit_put_u16(uint8_t* out, uint16_t value) {
  out[0] = (uint8_t)(value & 0xFFu);
  out[1] = (uint8_t)(value >> 8);
}

static inline void pamkit_put_u32(uint8_t* out, uint32_t value) {
  pamkit_put_u16(out, (uint16_t)(value & 0xFFFFu));
  pamkit_put_u16(out + 2, (uint16_t)(value >> 16));
}

static inline uint16_t pamkit_get_u16(const uint8_t* in) { return (uint16_t)(in[0] | ((uint16_t)in[1] << 8)); }

static inline uint32_t pamkit_get_u32(const uint8_t* in) {
  return (uint32_t)pamkit_get_u16(in) | ((uint32_t)pamkit_get_u16(in + 2) << 16);
}

/** Writes `frame` as PAMKIT_FRAME_SIZE bytes into `out`, sync bytes and CRC included. */
static inline void pamkit_frame_encode(const pamkit_frame* frame, uint8_t* out) {
  out[0] = PAMKIT_FRAME_SYNC0;
  out[1] = PAMKIT_FRAME_SYNC1;
  pamkit_put_u16(out + 2, frame->seq);
  pamkit_put_u32(out + 4, frame->time_us);
  pamkit_put_u16(out + 8, frame->counts[0]);
  pamkit_put_u16(out + 10, frame->counts[1]);
  out[12] = frame->oversample;
  out[13] = frame->dropped;
  pamkit_put_u16(out + PAMKIT_FRAME_CRC_OFFSET, pamkit_crc16(out + 2, PAMKIT_FRAME_CRC_OFFSET - 2));
}

/** Decodes PAMKIT_FRAME_SIZE bytes at `in`. Returns 1 and fills `frame` when the sync bytes,
 *  the CRC and the oversample count are all valid; returns 0 (frame untouched) otherwise. */
static inline int pamkit_frame_decode(const uint8_t* in, pamkit_frame* frame) {
  if (in[0] != PAMKIT_FRAME_SYNC0 || in[1] != PAMKIT_FRAME_SYNC1) return 0;
  if (pamkit_get_u16(in + PAMKIT_FRAME_CRC_OFFSET) != pamkit_crc16(in + 2, PAMKIT_FRAME_CRC_OFFSET - 2)) {
    return 0;
  }
  if (in[12] < 1 || in[12] > PAMKIT_OVERSAMPLE_MAX) return 0;
  frame->seq = pamkit_get_u16(in + 2);
  frame->time_us = pamkit_get_u32(in + 4);
  frame->counts[0] = pamkit_get_u16(in + 8);
  frame->counts[1] = pamkit_get_u16(in + 10);
  frame->oversample = in[12];
  frame->dropped = in[13];
  return 1;
}

#endif /* PAMKIT_FRAME_H */
