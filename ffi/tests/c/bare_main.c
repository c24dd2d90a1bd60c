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

static int handles[2] = {-1, -1};

/* SYS_OPEN of ":tt" for writing is the host's standard output (mode 4, "w") or standard error
 * (mode 8, "a"); SYS_WRITE writes. */
static void put_to(int err, const char *line) {
  if (handles[err] < 0) {
    const uint32_t open_args[3] = {(uint32_t)(uintptr_t)":tt", err ? 8u : 4u, 3};
    handles[err] = semihost(0x01 /* SYS_OPEN */, open_args);
  }
  uint32_t n = 0;
  while (line[n]) n++;
  const uint32_t write_args[3] = {(uint32_t)handles[err], (uint32_t)(uintptr_t)line, n};
  semihost(0x05 /* SYS_WRITE */, write_args);
}

static void put(const char *line) { put_to(0, line); }

#define PAINT 0xC0DEC0DEu

/* The stack high-water mark (bytes): the RAM between .bss and the stack was painted at reset;
 * the lowest word no longer painted is as deep as the stack went. Reported on standard error. */
static void report_stack(void) {
  const uint32_t *p = &_ebss;
  while (p < &_estack && *p == PAINT) p++;
  uint32_t used = (uint32_t)((uintptr_t)&_estack - (uintptr_t)p);
  char line[40] = "stack high-water: ";
  char digits[12];
  int n = 0, k = 18;
  do {
    digits[n++] = (char)('0' + used % 10);
    used /= 10;
  } while (used);
  while (n) line[k++] = digits[--n];
  const char *tail = " bytes\n";
  while (*tail) line[k++] = *tail++;
  line[k] = 0;
  put_to(1, line);
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
  {
    uint32_t *sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    for (dst = &_ebss; dst < sp - 16;) *dst++ = PAINT;
  }
#if defined(__ARM_FP)
  /* CPACR: full access to CP10 and CP11 (the FPU). */
  *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
  __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
  scenario_run(put);
  report_stack();
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
