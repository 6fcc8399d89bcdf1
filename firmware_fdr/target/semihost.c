/*
 * semihost.c - semihosting calls and a small number printer (no printf:
 * newlib's would dwarf the module being measured).
 */
#include "semihost.h"

#define SYS_WRITE0 0x04
#define SYS_EXIT 0x18
#define ADP_STOPPED_APPLICATION_EXIT 0x20026
#define ADP_STOPPED_RUNTIME_ERROR 0x20023

#define TIMER0_BASE 0x40000000u

static int sh_call(int op, const void *arg)
{
	register int r0 __asm__("r0") = op;
	register const void *r1 __asm__("r1") = arg;

	__asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
	return r0;
}

void sh_puts(const char *s)
{
	(void)sh_call(SYS_WRITE0, s);
}

void sh_put_uint(uint32_t v)
{
	char buf[12];
	int i = 11;

	buf[i] = '\0';
	do {
		buf[--i] = (char)('0' + v % 10u);
		v /= 10u;
	} while (v && i > 0);
	sh_puts(&buf[i]);
}

void sh_put_hex(uint32_t v)
{
	char buf[11] = "0x";
	int i;

	for (i = 0; i < 8; i++)
		buf[2 + i] = "0123456789abcdef"[(v >> (28 - 4 * i)) & 0xFu];
	buf[10] = '\0';
	sh_puts(buf);
}

void sh_put_double(double v)
{
	int e = 0, i;
	char buf[16];
	uint32_t m;

	if (v != v) {
		sh_puts("nan");
		return;
	}
	if (v < 0) {
		sh_puts("-");
		v = -v;
	}
	if (v == 0.0 || v > 1e300) {
		sh_puts(v == 0.0 ? "0" : "inf");
		return;
	}
	while (v >= 10.0 && e < 400) {
		v /= 10.0;
		e++;
	}
	while (v < 1.0 && e > -400) {
		v *= 10.0;
		e--;
	}
	m = (uint32_t)(v * 100000.0 + 0.5);
	for (i = 6; i >= 0; i--) {
		if (i == 1) {
			buf[i] = '.';
			continue;
		}
		buf[i] = (char)('0' + m % 10u);
		m /= 10u;
	}
	buf[7] = '\0';
	sh_puts(buf);
	sh_puts(e < 0 ? "e-" : "e+");
	sh_put_uint((uint32_t)(e < 0 ? -e : e));
}

void sh_exit(int ok)
{
	for (;;)
		(void)sh_call(SYS_EXIT, (const void *)(uintptr_t)(ok ?
			ADP_STOPPED_APPLICATION_EXIT :
			ADP_STOPPED_RUNTIME_ERROR));
}

void sh_timer_start(void)
{
	volatile uint32_t *t = (volatile uint32_t *)TIMER0_BASE;

	t[0] = 0u;		/* CTRL: stop */
	t[2] = 0xFFFFFFFFu;	/* RELOAD */
	t[1] = 0xFFFFFFFFu;	/* VALUE */
	t[0] = 1u;		/* CTRL: enable */
}

uint32_t sh_timer_now(void)
{
	return ((volatile uint32_t *)TIMER0_BASE)[1];
}
