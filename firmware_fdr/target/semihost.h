/*
 * semihost.h - ARM semihosting for the emulated target (test harness
 * only, never in the flight module): text out, and exit with a status.
 * ARM DUI 0471 "Semihosting", SYS_WRITE0 (0x04) and SYS_EXIT (0x18).
 */
#ifndef FDRFW_SEMIHOST_H
#define FDRFW_SEMIHOST_H

#include <stdint.h>

void sh_puts(const char *s);
void sh_put_uint(uint32_t v);
void sh_put_hex(uint32_t v);
/* A signed number with 6 significant digits, e.g. "-1.23456e-07". */
void sh_put_double(double v);
void sh_exit(int ok) __attribute__((noreturn));

/* CMSDK APB timer 0 of the MPS2 (25 MHz), for cycle counts under QEMU's
 * -icount: a free-running down-counter. */
void sh_timer_start(void);
uint32_t sh_timer_now(void);

#endif /* FDRFW_SEMIHOST_H */
