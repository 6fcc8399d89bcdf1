/*
 * startup.c - reset and fault vectors of the Cortex-M4F images (the
 * footprint image and the emulated test run): copy .data, clear .bss,
 * paint the stack for the high-water mark, enable the FPU, run main.
 */
#include <stdint.h>
#include <string.h>

extern uint32_t __data_load[], __data_start[], __data_end[];
extern uint32_t __bss_start[], __bss_end[];
extern uint32_t __stack_limit[], __stack_top[];

int main(void);
void fdrfw_reset(void);
void fdrfw_fault(void);

#define STACK_PAINT 0xC5C5C5C5u
#define CPACR (*(volatile uint32_t *)0xE000ED88u)

__attribute__((section(".vectors"), used))
static void (*const vectors[16])(void) = {
	(void (*)(void))(uintptr_t)__stack_top,
	fdrfw_reset,
	fdrfw_fault, fdrfw_fault, fdrfw_fault, fdrfw_fault, fdrfw_fault,
};

/*
 * Stack probing for the test harness: paint the free stack below the
 * caller, then after the call under test find the deepest word it
 * touched.  The result is the stack the callee used, libm included.
 */
__attribute__((noinline)) uintptr_t fdrfw_stack_paint(void)
{
	volatile uint32_t *p = __stack_limit;
	uintptr_t sp;

	__asm__ volatile("mov %0, sp" : "=r"(sp));
	/* Our own frame is below the caller's sp: stay 64 bytes clear. */
	while ((uintptr_t)p < sp - 64u)
		*p++ = STACK_PAINT;
	return sp;
}

uint32_t fdrfw_stack_used_since(uintptr_t sp)
{
	const uint32_t *p = __stack_limit;

	while ((uintptr_t)p < sp && *p == STACK_PAINT)
		p++;
	return (uint32_t)(sp - (uintptr_t)p);
}

void fdrfw_reset(void)
{
	uint32_t *s = __data_load, *d = __data_start;

	while (d < __data_end)
		*d++ = *s++;
	for (d = __bss_start; d < __bss_end; d++)
		*d = 0u;
	CPACR |= 0xFu << 20;	/* CP10, CP11 full access: the FPU */
	__asm__ volatile("dsb\n\tisb");
	(void)main();
	for (;;)
		;
}
