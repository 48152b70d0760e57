/* Emulator support for powerpc-linux-gnu.cmake, preloaded into test programs run under
 * qemu-ppc (LD_PRELOAD); never part of a product.
 *
 * glibc 2.36 (Debian 12) on 32-bit PowerPC executes the POWER9 instructions mffscrn /
 * mffscrni / mffsl on every CPU (in atan2, atan, the long double functions, ...): on a
 * CPU older than ISA 3.0 the hardware decodes them as plain mffs (the extra bits are
 * "don't care" for mffs), and glibc then sets the rounding mode itself. QEMU 7.2 treats
 * them as illegal on its 32-bit CPU models instead, so the program dies with SIGILL.
 * This handler does what the older hardware does: it rewrites such an instruction, where
 * it faulted, into the plain mffs it decodes as on those CPUs (so each site traps once),
 * and resumes there. Any other SIGILL stays fatal. */
#define _GNU_SOURCE
#include <signal.h>
#include <stdint.h>
#include <string.h>
#include <sys/mman.h>
#include <ucontext.h>
#include <unistd.h>

static void on_sigill(int sig, siginfo_t* info, void* context)
{
  (void)info;
  ucontext_t* uc = (ucontext_t*)context;
  mcontext_t* mc = uc->uc_mcontext.uc_regs;
  const uint32_t insn = *(const uint32_t*)mc->gregs[PT_NIP];
  /* Primary opcode 63, extended opcode 583 (mffs) with a non-zero field in bits 11-15:
   * mffsce (1), mffscdrn (20), mffscdrni (21), mffscrn (22), mffscrni (23), mffsl (24). */
  if ((insn >> 26) == 63 && ((insn >> 1) & 0x3FFu) == 583 && ((insn >> 16) & 31) != 0) {
    uint32_t* site = (uint32_t*)mc->gregs[PT_NIP];
    const uintptr_t page = (uintptr_t)site & ~((uintptr_t)sysconf(_SC_PAGESIZE) - 1);
    const size_t len = (size_t)sysconf(_SC_PAGESIZE);
    if (mprotect((void*)page, len, PROT_READ | PROT_WRITE | PROT_EXEC) == 0) {
      *site = insn & ~(31u << 16); /* mffs FRT */
      __builtin___clear_cache((char*)site, (char*)(site + 1));
      mprotect((void*)page, len, PROT_READ | PROT_EXEC);
      return; /* resume at the rewritten instruction */
    }
    /* Text not writable: execute it as mffs here and step over it. */
    union {
      double d;
      uint64_t u;
    } v;
    v.u = (uint32_t)mc->fpregs.fpscr;
    mc->fpregs.fpregs[(insn >> 21) & 31] = v.d;
    mc->gregs[PT_NIP] += 4;
    return;
  }
  signal(sig, SIG_DFL); /* a real illegal instruction: die of it on return */
}

__attribute__((constructor)) static void install_mffs_handler(void)
{
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_sigaction = on_sigill;
  sa.sa_flags = SA_SIGINFO;
  sigaction(SIGILL, &sa, 0);
}
