/* Arm semihosting (the debugger/emulator call interface: `bkpt 0xAB` on M-profile):
 * the firmware's only output and its exit status. QEMU needs
 * -semihosting-config enable=on,target=native. No C library stdio, no heap. */
#ifndef GYRO_FW_SEMIHOSTING_H
#define GYRO_FW_SEMIHOSTING_H

#ifdef __cplusplus
extern "C" {
#endif

/* Writes a NUL-terminated string to the host's console (SYS_WRITE0). */
void gyro_fw_write0(const char* text);

/* Ends the program with `status` as the emulator's exit status (SYS_EXIT_EXTENDED). */
__attribute__((noreturn)) void gyro_fw_exit(int status);

#ifdef __cplusplus
}
#endif

#endif
