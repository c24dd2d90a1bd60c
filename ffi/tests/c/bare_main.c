/* The C test scenario on bare metal (Cortex-M under QEMU): a vector table, a reset handler that
 * initialises .data and .bss (and the FPU where there is one), and the scenario's lines written
 * through ARM semihosting. The exit status is QEMU's: 0 when the scenario ran to its end. */
#include <stdint.h>

#include "scenario.h"

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;

static int semihost(int op, const void *arg) {
  register int r0 __asm__("r0") = op;
  register const void *r1 __asm__("r1") = arg;
  __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

static int stdout_handle = -1;

/* SYS_OPEN of ":tt" for writing ("w", mode 4) is the host's standard output; SYS_WRITE writes. */
static void put(const char *line) {
  if (stdout_handle < 0) {
    const uint32_t open_args[3] = {(uint32_t)(uintptr_t)":tt", 4, 3};
    stdout_handle = semihost(0x01 /* SYS_OPEN */, open_args);
  }
  uint32_t n = 0;
  while (line[n]) n++;
  const uint32_t write_args[3] = {(uint32_t)stdout_handle, (uint32_t)(uintptr_t)line, n};
  semihost(0x05 /* SYS_WRITE */, write_args);
}

static void __attribute__((noreturn)) stop(int ok) {
  /* SYS_EXIT with ADP_Stopped_ApplicationExit (status 0) or RunTimeErrorUnknown (status 1). */
  semihost(0x18, (const void *)(uintptr_t)(ok ? 0x20026u : 0x20023u));
  for (;;) {
  }
}

void reset_handler(void) {
  uint32_t *src = &_sidata, *dst = &_sdata;
  while (dst < &_edata) *dst++ = *src++;
  for (dst = &_sbss; dst < &_ebss;) *dst++ = 0;
#if defined(__ARM_FP)
  /* CPACR: full access to CP10 and CP11 (the FPU). */
  *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
  __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
  scenario_run(put);
  stop(1);
}

static void fault_handler(void) {
  put("fault\n");
  stop(0);
}

__attribute__((section(".vectors"), used)) static void (*const vectors[16])(void) = {
    (void (*)(void))(uintptr_t)&_estack, reset_handler, fault_handler, fault_handler,
    fault_handler, fault_handler, fault_handler, 0, 0, 0, 0, fault_handler, fault_handler, 0,
    fault_handler, fault_handler,
};
