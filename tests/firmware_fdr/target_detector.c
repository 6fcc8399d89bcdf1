/*
 * target_detector.c - a detector table (tetra3, k = 3: issue 28's flight
 * table version 3) in the flight module on the emulated Cortex-M4F
 * (qemu-system-arm -M mps2-an386, semihosting), with the checks
 * test_detector_float makes on the host: the table accepted; at every
 * node of its grid the module answers the table's false stars and P(DRS)
 * in float; the Sun's flag turns at the table's exclusion angle; another
 * exposure than the grid's is an invalid frame.  Then the cost of a frame
 * at the Sun's exclusion angle: instructions and stack.  Prints one
 * summary; exits 0 only when every check passed.
 */
#include <math.h>
#include <stdint.h>

#include "fdrfw/fdrfw.h"
#include "semihost.h"
#include "source_fdr.h"

#define INSNS_PER_TICK 40u	/* -icount shift=0, timer at 25 MHz */

extern const struct fdrfw_table fdrfw_det_table;
uintptr_t fdrfw_stack_paint(void);
uint32_t fdrfw_stack_used_since(uintptr_t sp);
void fdrfw_fault(void);

void fdrfw_fault(void)
{
	sh_puts("fdrfw-det-target: hard fault\n");
	sh_exit(0);
}

static unsigned failures;

static void check(int ok, const char *what, uint32_t i)
{
	if (ok)
		return;
	failures++;
	sh_puts("fdrfw-det-target: FAILED ");
	sh_puts(what);
	sh_puts(" at ");
	sh_put_uint(i);
	sh_puts("\n");
}

/* The grid's answers at its nodes (tolerances of test_detector_float). */
static unsigned check_nodes(struct fdrfw_ctx *ctx)
{
	const struct fdrfw_table *t = &fdrfw_det_table;
	struct fdrfw_source_result r;
	double per = (double)t->f_sun_ph_s_m2 * (double)t->t_exp_nominal_s *
		     (double)t->a_px_m2 * (double)t->k_px;
	unsigned i, n = 0;

	for (i = 0; i < t->n_det; i++) {
		float a = (float)(exp((double)t->det_u0 + i * (double)t->det_du) /
				  per);
		float lf = t->det_ln_false[i];

		fdrfw_grid_source(ctx, (stray_real)t->f_sun_ph_s_m2, a, a, &r);
		check(fabsf(r.p_drs - t->det_p_drs[i]) <= 2e-4f, "P(DRS)", i);
		if (lf > FDRFW_DET_LN_FLOOR + 1.0f)
			check(fabsf(r.ln_fdr - lf) <= 2e-3f + 2e-4f * fabsf(lf),
			      "ln false stars", i);
		n++;
	}
	return n;
}

/* One frame with the Sun at theta off the boresight (+z), the Moon and
 * the Earth behind. */
static void frame_at(struct fdrfw_ctx *ctx, float theta_deg,
		     struct fdrfw_output *out, uint32_t *insns,
		     uint32_t *stack)
{
	struct fdrfw_input in = { 0 };
	float th = theta_deg * 0.017453292f;
	uint32_t t0, t1;
	uintptr_t sp;

	in.q[0] = 1.0f;
	in.t_exp_s = fdrfw_det_table.t_exp_nominal_s;
	in.use_given_dirs = 1;
	in.sun_dir[0] = sinf(th);
	in.sun_dir[2] = cosf(th);
	in.moon_dir[2] = -1.0f;
	in.pos_km[2] = 42164.0f;	/* GEO over the pole: Earth behind */
	sp = fdrfw_stack_paint();
	t0 = sh_timer_now();
	(void)fdrfw_frame(ctx, &in, out);
	t1 = sh_timer_now();
	*stack = fdrfw_stack_used_since(sp);
	*insns = (t0 - t1) * INSNS_PER_TICK;	/* the timer counts down */
}

int main(void)
{
	const struct fdrfw_table *t = &fdrfw_det_table;
	struct fdrfw_source_result r;
	struct fdrfw_output out;
	struct fdrfw_ctx ctx;
	uint32_t insns, stack, insns2, stack2;
	unsigned nodes;

	sh_timer_start();
	if (fdrfw_init(&ctx, t) != FDRFW_OK || t->detector != 3u) {
		sh_puts("fdrfw-det-target: detector table rejected\n");
		sh_exit(0);
	}
	nodes = check_nodes(&ctx);
	check(fdrfw_point_source(&ctx, (stray_real)t->f_sun_ph_s_m2,
				 t->exclusion_sun_deg - 0.3f, 0, &r) == 0 &&
	      r.excluded, "Sun excluded 0.3 deg inside", 0);
	check(fdrfw_point_source(&ctx, (stray_real)t->f_sun_ph_s_m2,
				 t->exclusion_sun_deg + 0.3f, 0, &r) == 0 &&
	      !r.excluded, "Sun clear 0.3 deg outside", 0);
	frame_at(&ctx, t->exclusion_sun_deg + 1.0f, &out, &insns, &stack);
	frame_at(&ctx, t->exclusion_sun_deg + 1.0f, &out, &insns2, &stack2);
	check(!(out.flags & FDRFW_SUN_EXCLUDED) && out.p_drs[0] > 0.0f,
	      "frame 1 deg outside the exclusion angle", 0);
	check(fdrfw_set_exposure(&ctx, 0.5f * t->t_exp_nominal_s) ==
	      FDRFW_EINPUT, "another exposure refused", 0);
	sh_puts("fdrfw-det-target: tetra3 table, ");
	sh_put_uint(nodes);
	sh_puts(" nodes checked, Sun exclusion ");
	sh_put_double((double)t->exclusion_sun_deg);
	sh_puts(" deg, ");
	sh_put_uint(failures);
	sh_puts(" failures\nfdrfw-det-target: a frame at exclusion + 1 deg: ");
	sh_put_uint(insns);
	sh_puts(" instructions, stack ");
	sh_put_uint(stack);
	sh_puts(" bytes; the same frame again ");
	sh_put_uint(insns2);
	sh_puts(" instructions, stack ");
	sh_put_uint(stack2);
	sh_puts(" bytes (flags ");
	sh_put_hex(out.flags);
	sh_puts(", Earth limb ");
	sh_put_double((double)out.theta_deg[FDRFW_EARTH]);
	sh_puts(" deg)\n");
	sh_exit(failures == 0 && nodes > 0);
}
