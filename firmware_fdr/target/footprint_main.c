/*
 * footprint_main.c - the smallest image that uses the whole module: init
 * with the generated flight table, then one frame per loop from inputs
 * the compiler cannot see through.  `make firmware` sizes this image.
 */
#include "fdrfw/fdrfw.h"

extern const struct fdrfw_table fdrfw_flight_table;

void fdrfw_fault(void);

void fdrfw_fault(void)
{
	for (;;)
		;
}

/* Inputs and outputs at a fixed mailbox address, as a flight loop would
 * exchange them with the tracker, so the image's .bss is the module's. */
#define MAILBOX 0x20200000u
#define FDRFW_IN (*(const volatile struct fdrfw_input *)MAILBOX)
#define FDRFW_OUT (*(volatile struct fdrfw_output *)(MAILBOX + 0x100u))

int main(void)
{
	struct fdrfw_ctx ctx;

	(void)fdrfw_init(&ctx, &fdrfw_flight_table);
	for (;;) {
		struct fdrfw_input in = *(const struct fdrfw_input *)&FDRFW_IN;
		struct fdrfw_output out;

		(void)fdrfw_frame(&ctx, &in, &out);
		*(struct fdrfw_output *)&FDRFW_OUT = out;
	}
}
