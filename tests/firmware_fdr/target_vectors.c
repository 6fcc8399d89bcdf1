/*
 * target_vectors.c - the shared vectors on the emulated Cortex-M4F
 * (qemu-system-arm -M mps2-an386, semihosting): every vector through a
 * fresh context, checked as on the host; then instructions and stack per
 * frame.  Prints one summary and exits 0 only when all agree.
 */
#include <stdint.h>

#include "fdrfw/fdrfw.h"
#include "semihost.h"
#include "vectors.h"
#include "../vectors/fdrfw_vectors.h"

#define N_VEC (sizeof(fdrfw_vectors) / sizeof(fdrfw_vectors[0]))
/* QEMU -icount shift=0: one instruction per ns; timer at 25 MHz. */
#define INSNS_PER_TICK 40u

extern const struct fdrfw_table fdrfw_flight_table;
uintptr_t fdrfw_stack_paint(void);
uint32_t fdrfw_stack_used_since(uintptr_t sp);
void fdrfw_fault(void);

void fdrfw_fault(void)
{
	sh_puts("fdrfw-target: hard fault\n");
	sh_exit(0);
}

static void report_failure(unsigned i, int field, const struct fdrfw_output *o)
{
	sh_puts("fdrfw-target: vector ");
	sh_put_uint(i);
	sh_puts(" field ");
	sh_put_uint((uint32_t)field);
	sh_puts(" flags ");
	sh_put_hex(o->flags);
	sh_puts(" ln_fdr ");
	sh_put_double((double)o->ln_fdr[0]);
	sh_puts(" ");
	sh_put_double((double)o->ln_fdr[1]);
	sh_puts("\n");
}

/* 2,000,001 instructions (1e6 x subs+bne, plus the mov): the check that
 * timer ticks x 40 counts instructions under -icount shift=0. */
static uint32_t calibrate(void)
{
	uint32_t t0 = sh_timer_now(), t1;

	__asm__ volatile("mov r0, %0\n1:\n\tsubs r0, r0, #1\n\tbne 1b"
			 : : "r"(1000000u) : "r0", "cc");
	t1 = sh_timer_now();
	return (t0 - t1) * INSNS_PER_TICK;
}

int main(void)
{
	uint32_t ticks_max = 0, ticks_sum = 0, stack_max = 0, first_max = 0;
	uint32_t steady_max = 0;
	double worst = 0.0;
	unsigned i, ok = 0;

	sh_timer_start();
	for (i = 0; i < N_VEC; i++) {
		struct fdrfw_ctx ctx;
		struct fdrfw_input in;
		struct fdrfw_output out;
		uint32_t t0, t1, used;
		uintptr_t sp;
		int bad;

		if (fdrfw_init(&ctx, &fdrfw_flight_table) != FDRFW_OK) {
			sh_puts("fdrfw-target: flight table rejected\n");
			sh_exit(0);
		}
		fdrfw_vector_input(&fdrfw_vectors[i], &in);
		sp = fdrfw_stack_paint();
		t0 = sh_timer_now();
		(void)fdrfw_frame(&ctx, &in, &out);
		t1 = sh_timer_now();
		used = fdrfw_stack_used_since(sp);
		bad = fdrfw_vector_check(&fdrfw_vectors[i], &out, &worst);
		if (bad)
			report_failure(i, bad, &out);
		else
			ok++;
		first_max = t0 - t1 > first_max ? t0 - t1 : first_max;
		stack_max = used > stack_max ? used : stack_max;
		/* Steady state: the same exposure again, threshold cached. */
		sp = fdrfw_stack_paint();
		t0 = sh_timer_now();
		(void)fdrfw_frame(&ctx, &in, &out);
		t1 = sh_timer_now();
		used = fdrfw_stack_used_since(sp);
		steady_max = used > steady_max ? used : steady_max;
		ticks_sum += t0 - t1;	/* the timer counts down */
		ticks_max = t0 - t1 > ticks_max ? t0 - t1 : ticks_max;
	}
	sh_puts("fdrfw-target: ");
	sh_put_uint(ok);
	sh_puts("/");
	sh_put_uint(N_VEC);
	sh_puts(" vectors agree, worst |d ln FDR| ");
	sh_put_double(worst);
	sh_puts("\nfdrfw-target: instructions per frame mean ");
	sh_put_uint(ticks_sum / N_VEC * INSNS_PER_TICK);
	sh_puts(" max ");
	sh_put_uint(ticks_max * INSNS_PER_TICK);
	sh_puts("; first frame at a new exposure (I_sdt recomputed) max ");
	sh_put_uint(first_max * INSNS_PER_TICK);
	sh_puts("\nfdrfw-target: stack per frame max ");
	sh_put_uint(steady_max);
	sh_puts(" bytes; at a new exposure ");
	sh_put_uint(stack_max);
	sh_puts(" bytes (painted, libm included, +-64)\n");
	sh_puts("fdrfw-target: calibration 2000001 instructions counted as ");
	sh_put_uint(calibrate());
	sh_puts("\n");
	sh_exit(ok == N_VEC);
}
