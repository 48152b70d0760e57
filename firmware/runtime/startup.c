/* Cortex-M startup for the MPS2 images (and real parts with the same layout); no CMSIS.
 * Reset: enable the FPU (CPACR) -> copy .data -> zero .bss -> C++ static constructors ->
 * main() -> exit with main's return value through semihosting.
 * Also: the semihosting calls, a fault handler that exits QEMU with status 1 (a crash
 * never hangs CI) and the assert handler (prints, exits 134 like abort on a host). */
#include <stdint.h>

#include "semihosting.h"

extern uint32_t __stack_top[];
extern uint32_t __data_load__[], __data_start__[], __data_end__[];
extern uint32_t __bss_start__[], __bss_end__[];

int main(void);
void __libc_init_array(void); /* newlib: runs .preinit_array, _init, .init_array */

/* -nostartfiles drops crti.o (_init/_fini, called by __libc_init_array) and crtbegin.o
 * (__dso_handle, referenced when a static object's destructor is registered). */
void _init(void) {}
void _fini(void) {}
void* __dso_handle = 0;

/* Semihosting call: r0 = operation, r1 = parameter; the result comes back in r0. */
static inline int sh_call(int op, const void* arg)
{
  register int r0 __asm__("r0") = op;
  register const void* r1 __asm__("r1") = arg;
  __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

enum {
  kSysWrite0 = 0x04,
  kSysExitExtended = 0x20,
  kAdpStoppedApplicationExit = 0x20026,
};

void gyro_fw_write0(const char* text) { (void)sh_call(kSysWrite0, text); }

void gyro_fw_exit(int status)
{
  const uint32_t block[2] = {kAdpStoppedApplicationExit, (uint32_t)status};
  (void)sh_call(kSysExitExtended, block);
  for (;;) {
  }
}

/* newlib's assert() (and so Eigen's eigen_assert, EIGEN_NO_MALLOC) calls this. Defining
 * it here keeps newlib's version, which prints through stdio (and allocates), out. */
__attribute__((noreturn)) void __assert_func(const char* file, int line, const char* func,
                                             const char* expr)
{
  (void)line;
  gyro_fw_write0("*** assertion failed: ");
  gyro_fw_write0(expr);
  gyro_fw_write0(" in ");
  gyro_fw_write0(func ? func : "?");
  gyro_fw_write0(" (");
  gyro_fw_write0(file);
  gyro_fw_write0(")\n");
  gyro_fw_exit(134);
}

/* Any fault or unexpected interrupt: say so and make QEMU exit non-zero. */
void Default_Handler(void)
{
  gyro_fw_write0("*** CPU fault (HardFault/UsageFault/...) ***\n");
  gyro_fw_exit(1);
}

__attribute__((noreturn)) void Reset_Handler(void)
{
  /* 1. FPU on: CPACR.CP10/CP11 = full access. Must precede any floating-point
   *    instruction (the compiler may use s/d registers anywhere once main runs). */
#if defined(__ARM_FP)
  *(volatile uint32_t*)0xE000ED88u |= (0xFu << 20);
  __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
  /* 2. .data: FLASH -> RAM;  3. .bss = 0 */
  uint32_t* src = __data_load__;
  uint32_t* dst = __data_start__;
  while (dst < __data_end__) *dst++ = *src++;
  for (dst = __bss_start__; dst < __bss_end__;) *dst++ = 0;
  /* 4. C++ static constructors (test registration), main, exit */
  __libc_init_array();
  gyro_fw_exit(main());
}

void NMI_Handler(void) __attribute__((weak, alias("Default_Handler")));
void HardFault_Handler(void) __attribute__((weak, alias("Default_Handler")));
void MemManage_Handler(void) __attribute__((weak, alias("Default_Handler")));
void BusFault_Handler(void) __attribute__((weak, alias("Default_Handler")));
void UsageFault_Handler(void) __attribute__((weak, alias("Default_Handler")));
void SVC_Handler(void) __attribute__((weak, alias("Default_Handler")));
void DebugMon_Handler(void) __attribute__((weak, alias("Default_Handler")));
void PendSV_Handler(void) __attribute__((weak, alias("Default_Handler")));
void SysTick_Handler(void) __attribute__((weak, alias("Default_Handler")));

/* The 16 core vectors (the MPS2 peripheral interrupts are not used). */
__attribute__((section(".isr_vector"), used)) void (*const g_vectors[16])(void) = {
    (void (*)(void))__stack_top, /* initial MSP */
    Reset_Handler,
    NMI_Handler,
    HardFault_Handler,
    MemManage_Handler,
    BusFault_Handler,
    UsageFault_Handler,
    0,
    0,
    0,
    0,
    SVC_Handler,
    DebugMon_Handler,
    0,
    PendSV_Handler,
    SysTick_Handler,
};
