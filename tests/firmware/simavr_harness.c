/* simavr_harness: runs the real logger firmware (an avr-gcc ELF) as an ATmega2560 at 16 MHz in
 * simavr, drives its analog inputs A0 and A1 with known voltage waveforms and exposes UART0 on a
 * pseudo-terminal, reached through a symlink (like a /dev/serial/by-id/ name).
 *
 * It behaves like a Mega on USB: the board restarts whenever the port is opened (the auto-reset
 * on DTR), stops when nobody listens, and can inject faults into the byte stream on the way to the
 * host. It writes what it did, so that a test can hold the host reader to it:
 *
 *   --truth FILE    one line per event, in order:
 *                     C <boot> <channel> <mV>        an ADC conversion and the voltage it was served
 *                     F <boot> <seq> <damaged>       a frame the firmware sent (damaged: 0 or 1)
 *                     X <kind> <boot> <seq> <bytes>  a fault: kind garbage|flip|drop|reset|unplug,
 *                                                    at that frame, <bytes> bytes of it skipped
 *   --summary FILE  key=value totals, written (atomically) when the run is over.
 *
 * Usage: simavr_harness --firmware ELF --link PATH --seconds S [--truth FILE] [--summary FILE]
 *                       [--fault-every N] [--seed N] [--realtime]
 *   --fault-every N  every N frames inject the next fault of: garbage, flip, drop, reset, unplug
 *   --realtime       never run ahead of the wall clock (for trying `pamkit log` by hand)
 *
 * Exit status 0 when the simulated time was run and the host closed the port afterwards.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <avr_adc.h>
#include <avr_uart.h>
#include <sim_avr.h>
#include <sim_elf.h>
#include <sim_io.h>
#include <sim_irq.h>

#include "pamkit_frame.h"

#define VREF_MV 5000u /* AVCC of the simulated Mega */
#define OUT_CAPACITY 65536

enum fault_kind { FAULT_GARBAGE, FAULT_FLIP, FAULT_DROP, FAULT_RESET, FAULT_UNPLUG, FAULT_KINDS };
static const char* const kFaultNames[FAULT_KINDS] = {"garbage", "flip", "drop", "reset", "unplug"};

typedef struct harness {
  avr_t* avr;
  avr_irq_t* adc_in[2];
  const char* link;
  FILE* truth;
  int master;
  uint64_t cycles; /* simulated cycles since start, across resets */
  avr_cycle_count_t last_cycle;
  unsigned boot;
  /* the stream as the firmware sends it */
  int in_banner;      /* inside a banner line */
  unsigned frame_pos; /* byte index within the current frame */
  uint8_t frame[PAMKIT_FRAME_SIZE];
  unsigned long frames; /* frames sent since start */
  /* fault plan */
  unsigned long fault_every;
  unsigned next_fault;
  unsigned long last_fault_at; /* frame count at the last fault: one fault per count */
  int fault_here;              /* fault planned for the current frame, or -1 */
  unsigned fault_byte;         /* which byte of the frame it hits */
  int pending;                 /* FAULT_RESET / FAULT_UNPLUG to perform after this batch, or -1 */
  int muted;                   /* the board is "gone" until the pending fault is performed */
  uint32_t rng;
  /* bytes on their way to the pty */
  uint8_t out[OUT_CAPACITY];
  size_t out_len;
  /* totals */
  unsigned long damaged, damaged_bytes, garbage_bytes, faults[FAULT_KINDS], bytes_written;
  unsigned long conversions;
  /* what the firmware itself reports: sequence gaps in the clean stream and its dropped counts */
  int have_seq;
  uint16_t last_seq;
  unsigned long seq_gaps, seq_missing, device_dropped;
} harness;

/* elf_read_firmware allocates the firmware's sections and symbols for the caller, and simavr 1.6
 * has no function that frees them; avr_load_firmware copied the code into the AVR's own memory. */
static void free_firmware(elf_firmware_t* fw) {
  for (uint32_t i = 0; i < fw->symbolcount; ++i) free(fw->symbol[i]);
  free(fw->symbol);
  free(fw->flash);
  free(fw->eeprom);
  free(fw->fuse);
  free(fw->lockbits);
}

static void die(const char* what) {
  fprintf(stderr, "simavr_harness: %s: %s\n", what, strerror(errno));
  exit(2);
}

static uint32_t next_random(harness* h) { /* xorshift32, seeded: runs are reproducible */
  h->rng ^= h->rng << 13;
  h->rng ^= h->rng >> 17;
  h->rng ^= h->rng << 5;
  return h->rng;
}

static double sim_seconds(const harness* h) { return (double)h->cycles / h->avr->frequency; }

/* The injected voltages [mV], functions of simulated time: A0 sweeps the whole ADC range (a
 * pressure transducer from 0 to full scale and back), A1 moves like a TMP36 around 25 degC. */
static uint32_t waveform_mV(int channel, double t) {
  double v;
  if (channel == 0) {
    v = 2500.0 - 2500.0 * cos(2.0 * M_PI * t / 3.7);
  } else {
    v = 750.0 + 40.0 * sin(2.0 * M_PI * t / 11.0) + 8.0 * sin(2.0 * M_PI * t / 0.9);
  }
  if (v < 0) v = 0;
  if (v > VREF_MV) v = VREF_MV;
  return (uint32_t)lround(v);
}

/* A conversion starts: serve the channel its voltage now (simavr latches it when ADCL is read). */
static void adc_trigger(avr_irq_t* irq, uint32_t value, void* param) {
  (void)irq;
  harness* h = (harness*)param;
  union {
    avr_adc_mux_t mux;
    uint32_t v;
  } e = {.v = value};
  if (e.mux.kind != ADC_MUX_SINGLE || e.mux.src > 1) return;
  const uint32_t mV =
      waveform_mV(e.mux.src, sim_seconds(h) + (double)(h->avr->cycle - h->last_cycle) / h->avr->frequency);
  avr_raise_irq(h->adc_in[e.mux.src], mV);
  ++h->conversions;
  if (h->truth) fprintf(h->truth, "C %u %u %u\n", h->boot, (unsigned)e.mux.src, mV);
}

static void emit(harness* h, uint8_t byte) {
  if (h->out_len == OUT_CAPACITY) {
    fprintf(stderr, "simavr_harness: output buffer overflow\n");
    exit(2);
  }
  h->out[h->out_len++] = byte;
}

static void plan_fault(harness* h) {
  h->fault_here = -1;
  if (h->fault_every && h->frames > 0 && h->frames % h->fault_every == 0 && h->frames != h->last_fault_at) {
    h->last_fault_at = h->frames;
    h->fault_here = (int)(h->next_fault % FAULT_KINDS);
    ++h->next_fault;
    /* flips and drops hit a byte after the sync pair (a hit sync pair is found too, but as a
     * gap only, not as a checksum error); resets and unplugs cut the frame in the middle */
    h->fault_byte = h->fault_here == FAULT_FLIP || h->fault_here == FAULT_DROP
                        ? 2 + next_random(h) % (PAMKIT_FRAME_SIZE - 2)
                        : PAMKIT_FRAME_SIZE / 2;
  }
}

/* A whole frame went out: record it, with what the fault (if any) did to it. */
static void frame_done(harness* h) {
  pamkit_frame decoded;
  if (!pamkit_frame_decode(h->frame, &decoded)) {
    fprintf(stderr, "simavr_harness: the firmware sent a frame that does not decode\n");
    exit(2);
  }
  const int damaged = h->fault_here == FAULT_FLIP || h->fault_here == FAULT_DROP;
  if (h->truth) fprintf(h->truth, "F %u %u %d\n", h->boot, decoded.seq, damaged);
  if (h->have_seq && (uint16_t)(decoded.seq - h->last_seq) != 1) {
    ++h->seq_gaps;
    h->seq_missing += (uint16_t)(decoded.seq - h->last_seq - 1);
  }
  h->have_seq = 1;
  h->last_seq = decoded.seq;
  h->device_dropped += decoded.dropped;
  if (damaged) {
    const unsigned bytes = h->fault_here == FAULT_FLIP ? PAMKIT_FRAME_SIZE : PAMKIT_FRAME_SIZE - 1;
    ++h->damaged;
    h->damaged_bytes += bytes;
    if (h->truth) fprintf(h->truth, "X %s %u %u %u\n", kFaultNames[h->fault_here], h->boot, decoded.seq, bytes);
  }
  ++h->frames;
}

/* Every byte the firmware writes to UDR0. */
static void uart_output(avr_irq_t* irq, uint32_t value, void* param) {
  (void)irq;
  harness* h = (harness*)param;
  const uint8_t byte = (uint8_t)value;
  if (h->muted) return;
  if (h->frame_pos == 0 && !h->in_banner && byte == '#') h->in_banner = 1;
  if (h->in_banner) {
    emit(h, byte);
    if (byte == '\n') h->in_banner = 0;
    return;
  }
  if (h->frame_pos == 0) {
    plan_fault(h);
    if (h->fault_here == FAULT_GARBAGE) {
      /* random bytes, salted with sync pairs and a '#' so that the decoder must try and reject
       * false frames and false banners */
      const unsigned length = 20 + next_random(h) % 60;
      for (unsigned i = 0; i < length; ++i) {
        const uint32_t r = next_random(h);
        emit(h, (r & 0x700) == 0 ? PAMKIT_FRAME_SYNC0 : (r & 0x7000) == 0 ? '#' : (uint8_t)r);
        if ((r & 0x700) == 0 && i + 1 < length) {
          emit(h, PAMKIT_FRAME_SYNC1);
          ++i;
        }
      }
      h->garbage_bytes += length;
      ++h->faults[FAULT_GARBAGE];
      if (h->truth) fprintf(h->truth, "X garbage %u - %u\n", h->boot, length);
    }
  }
  h->frame[h->frame_pos] = byte;
  const unsigned pos = h->frame_pos++;
  if (h->fault_here == FAULT_FLIP && pos == h->fault_byte) {
    emit(h, byte ^ (uint8_t)(1u << (next_random(h) % 8)));
    ++h->faults[FAULT_FLIP];
  } else if (h->fault_here == FAULT_DROP && pos == h->fault_byte) {
    ++h->faults[FAULT_DROP];
  } else if ((h->fault_here == FAULT_RESET || h->fault_here == FAULT_UNPLUG) && pos == h->fault_byte) {
    /* the board resets (or the cable is pulled) half way through this frame */
    h->pending = h->fault_here;
    h->muted = 1;
    h->damaged_bytes += h->fault_byte;
    ++h->damaged;
    ++h->faults[h->fault_here];
    if (h->truth) fprintf(h->truth, "X %s %u %lu %u\n", kFaultNames[h->fault_here], h->boot, h->frames, h->fault_byte);
    return;
  } else {
    emit(h, byte);
  }
  if (h->frame_pos == PAMKIT_FRAME_SIZE) {
    frame_done(h);
    h->frame_pos = 0;
  }
}

static void wall_sleep(double seconds) {
  struct timespec ts = {(time_t)seconds, (long)((seconds - (time_t)seconds) * 1e9)};
  nanosleep(&ts, NULL);
}

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* A new pty, made raw, reached through the symlink (replaced atomically). */
static void plug_in(harness* h) {
  h->master = posix_openpt(O_RDWR | O_NOCTTY);
  if (h->master < 0 || grantpt(h->master) || unlockpt(h->master)) die("posix_openpt");
  /* A master whose slave was never opened does not report POLLHUP; open and close the slave
   * once, so that poll() tells when the host has the port open (port_open()). */
  const int once = open(ptsname(h->master), O_RDWR | O_NOCTTY);
  if (once < 0) die("open pty slave");
  close(once);
  /* On Linux the master's termios are the slave's: make the line raw before anyone opens it,
   * or the line discipline would echo, translate CR and swallow XON/XOFF bytes. */
  struct termios raw;
  if (tcgetattr(h->master, &raw)) die("tcgetattr");
  cfmakeraw(&raw);
  if (tcsetattr(h->master, TCSANOW, &raw)) die("tcsetattr");
  const char* slave = ptsname(h->master);
  if (!slave) die("ptsname");
  char temporary[4096];
  snprintf(temporary, sizeof temporary, "%s.new", h->link);
  unlink(temporary);
  if (symlink(slave, temporary) || rename(temporary, h->link)) die("symlink");
}

static void unplug(harness* h) {
  close(h->master);
  h->master = -1;
  unlink(h->link);
}

/* Has a host got the port open? (A pty master reports POLLHUP while no slave is open.) */
static int port_open(const harness* h) {
  struct pollfd p = {h->master, POLLOUT, 0};
  if (poll(&p, 1, 0) < 0) die("poll");
  return !(p.revents & POLLHUP);
}

/* Bytes sent that the host has not read yet: the input queue of the pty's slave side, which the
 * harness opens for the look (a second open of the slave changes nothing the host sees); -1 if it
 * cannot look. */
static int unread_bytes(const harness* h) {
  const int fd = open(ptsname(h->master), O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) return -1;
  int count = 0;
  if (ioctl(fd, FIONREAD, &count)) count = -1;
  close(fd);
  return count;
}

/* Waits until the host has read everything sent, however slowly a loaded machine runs it, so that
 * pulling the cable loses only the frame it cuts. The kernel moves written bytes to the slave's
 * queue asynchronously: the queue must stay empty for a while (20 looks 10 ms apart) before the
 * host is taken to have read it all. Gives up after timeout_s (a host that stopped reading). */
static void wait_until_read(const harness* h, double timeout_s) {
  const double until = wall_now() + timeout_s;
  int empty_looks = 0;
  while (empty_looks < 20 && wall_now() < until) {
    empty_looks = unread_bytes(h) == 0 ? empty_looks + 1 : 0;
    wall_sleep(0.01);
  }
}

static int wait_for_open(const harness* h, double timeout_s) {
  const double until = wall_now() + timeout_s;
  while (!port_open(h)) {
    if (wall_now() > until) return 0;
    wall_sleep(0.002);
  }
  wall_sleep(0.02); /* let the host finish configuring the port (raw mode) before bytes arrive */
  return 1;
}

/* The board restarts, as a Mega does when its port is opened or its power comes back. */
static void board_reset(harness* h, int count_boot) {
  avr_reset(h->avr);
  h->last_cycle = h->avr->cycle;
  if (count_boot) ++h->boot;
  h->have_seq = 0;
  h->in_banner = 0;
  h->frame_pos = 0;
  h->fault_here = -1;
  h->muted = 0;
}

/* Hands the buffered bytes to the pty; blocks while the host's side is full, so the simulation
 * waits for a slow reader instead of losing bytes. Returns 0 if the host closed the port. */
static int flush_out(harness* h) {
  size_t done = 0;
  while (done < h->out_len) {
    const ssize_t n = write(h->master, h->out + done, h->out_len - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EIO) return 0;
      die("write to pty");
    }
    done += (size_t)n;
  }
  h->bytes_written += done;
  h->out_len = 0;
  return 1;
}

static const char* option(int argc, char** argv, const char* name, const char* fallback) {
  for (int i = 1; i + 1 < argc; ++i)
    if (!strcmp(argv[i], name)) return argv[i + 1];
  return fallback;
}

static int flag(int argc, char** argv, const char* name) {
  for (int i = 1; i < argc; ++i)
    if (!strcmp(argv[i], name)) return 1;
  return 0;
}

int main(int argc, char** argv) {
  const char* firmware = option(argc, argv, "--firmware", NULL);
  const char* link = option(argc, argv, "--link", NULL);
  const char* truth = option(argc, argv, "--truth", NULL);
  const char* summary = option(argc, argv, "--summary", NULL);
  const double seconds = atof(option(argc, argv, "--seconds", "10"));
  const int realtime = flag(argc, argv, "--realtime");
  if (!firmware || !link || !(seconds > 0)) {
    fprintf(stderr,
            "usage: simavr_harness --firmware ELF --link PATH --seconds S [--truth FILE] "
            "[--summary FILE] [--fault-every N] [--seed N] [--realtime]\n");
    return 2;
  }

  static harness h;
  memset(&h, 0, sizeof h);
  h.link = link;
  h.fault_every = strtoul(option(argc, argv, "--fault-every", "0"), NULL, 10);
  h.rng = (uint32_t)strtoul(option(argc, argv, "--seed", "12345"), NULL, 10) | 1u;
  h.fault_here = -1;
  h.pending = -1;
  if (truth && !(h.truth = fopen(truth, "w"))) die(truth);

  elf_firmware_t fw;
  memset(&fw, 0, sizeof fw);
  if (elf_read_firmware(firmware, &fw) != 0) {
    fprintf(stderr, "simavr_harness: cannot read firmware %s\n", firmware);
    return 2;
  }
  strcpy(fw.mmcu, "atmega2560");
  fw.frequency = 16000000;
  fw.vcc = fw.avcc = fw.aref = VREF_MV;
  h.avr = avr_make_mcu_by_name(fw.mmcu);
  if (!h.avr) {
    fprintf(stderr, "simavr_harness: simavr has no atmega2560\n");
    return 2;
  }
  avr_init(h.avr);
  h.avr->log = LOG_ERROR;
  avr_load_firmware(h.avr, &fw);
  h.avr->vcc = h.avr->avcc = h.avr->aref = VREF_MV;

  uint32_t uart_flags = 0; /* no console echo, no usleep() when the firmware polls UCSR0A */
  avr_ioctl(h.avr, AVR_IOCTL_UART_SET_FLAGS('0'), &uart_flags);
  avr_irq_register_notify(avr_io_getirq(h.avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT), uart_output, &h);
  avr_irq_register_notify(avr_io_getirq(h.avr, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_OUT_TRIGGER), adc_trigger, &h);
  h.adc_in[0] = avr_io_getirq(h.avr, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC0);
  h.adc_in[1] = avr_io_getirq(h.avr, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC1);

  plug_in(&h);
  printf("simavr_harness: ATmega2560 at 16 MHz, UART0 on %s -> %s\n", link, ptsname(h.master));
  fflush(stdout);
  if (!wait_for_open(&h, 60)) {
    fprintf(stderr, "simavr_harness: nobody opened %s within 60 s\n", link);
    return 3;
  }
  board_reset(&h, 0);

  const double wall_start = wall_now();
  unsigned reopened = 0, unplugged = 0;
  while (sim_seconds(&h) < seconds) {
    for (int i = 0; i < 4000; ++i) {
      const int state = avr_run(h.avr);
      if (state == cpu_Done || state == cpu_Crashed) {
        fprintf(stderr, "simavr_harness: the AVR stopped (state %d) at %.6f s\n", state, sim_seconds(&h));
        return 4;
      }
    }
    h.cycles += h.avr->cycle - h.last_cycle;
    h.last_cycle = h.avr->cycle;
    int open = flush_out(&h) && port_open(&h);
    if (h.pending == FAULT_RESET) {
      board_reset(&h, 1);
      h.pending = -1;
    } else if (h.pending == FAULT_UNPLUG) {
      wait_until_read(&h, 60); /* the host reads what was sent before the cable comes out */
      unplug(&h);
      ++unplugged;
      wall_sleep(0.5);
      plug_in(&h);
      if (!wait_for_open(&h, 30)) {
        fprintf(stderr, "simavr_harness: the host did not reopen %s within 30 s\n", link);
        return 3;
      }
      board_reset(&h, 1); /* power comes back with the cable */
      h.pending = -1;
      continue;
    }
    if (!open) {
      /* the host closed the port: the board resets when it is opened again */
      if (!wait_for_open(&h, 60)) {
        fprintf(stderr, "simavr_harness: port closed at %.3f s simulated and not reopened\n", sim_seconds(&h));
        return 3;
      }
      ++reopened;
      h.out_len = 0;
      board_reset(&h, 1);
    }
    if (realtime) {
      const double ahead = sim_seconds(&h) - (wall_now() - wall_start);
      if (ahead > 0.005) wall_sleep(ahead);
    }
  }
  flush_out(&h);
  const double wall = wall_now() - wall_start;
  if (h.truth) fclose(h.truth);

  if (summary) {
    char temporary[4096];
    snprintf(temporary, sizeof temporary, "%s.tmp", summary);
    FILE* out = fopen(temporary, "w");
    if (!out) die(temporary);
    fprintf(out,
            "simulated_s=%.6f\nwall_s=%.3f\nframes=%lu\ndamaged_frames=%lu\ndamaged_bytes=%lu\n"
            "garbage_bytes=%lu\nbytes_written=%lu\nconversions=%lu\nboots=%u\nreopened=%u\n",
            sim_seconds(&h), wall, h.frames, h.damaged, h.damaged_bytes, h.garbage_bytes, h.bytes_written,
            h.conversions, h.boot + 1, reopened);
    for (int k = 0; k < FAULT_KINDS; ++k) fprintf(out, "fault_%s=%lu\n", kFaultNames[k], h.faults[k]);
    fprintf(out, "unplugged=%u\nseq_gaps=%lu\nseq_missing=%lu\ndevice_dropped=%lu\n", unplugged, h.seq_gaps,
            h.seq_missing, h.device_dropped);
    fclose(out);
    if (rename(temporary, summary)) die(summary);
  }
  printf("simavr_harness: %.2f s simulated in %.2f s, %lu frames, %lu damaged\n", sim_seconds(&h), wall, h.frames,
         h.damaged);
  fflush(stdout);
  /* wait for the host to let go of the port, so that it can read everything first */
  for (int i = 0; i < 3000 && port_open(&h); ++i) wall_sleep(0.01);
  unplug(&h);
  free_firmware(&fw);
  return 0;
}
