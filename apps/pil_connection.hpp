// The host's end of the processor-in-the-loop serial line: a client of QEMU's UNIX-socket
// chardev (-chardev socket,path=...,server=on -serial chardev:<id>), and the QEMU process
// when gyro_sil starts it. Failures throw RunError with what went wrong.
#pragma once

#include <sys/types.h>

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace gyro::sil {

class SerialSocket {
 public:
  // Connects to the socket at `path`, retrying for up to `wait_s` while `still_starting()`
  // says the server may still appear.
  SerialSocket(const std::string& path, double wait_s, const std::function<bool()>& still_starting);
  SerialSocket(const SerialSocket&) = delete;
  SerialSocket& operator=(const SerialSocket&) = delete;
  ~SerialSocket();

  void write(std::span<const std::uint8_t> bytes);
  // The next byte; throws after `timeout_s` of silence or when the target closed the line.
  [[nodiscard]] std::uint8_t read_byte(double timeout_s);
  // Waits until the other end closes the line (bytes still arriving are dropped); false after
  // `timeout_s`.
  [[nodiscard]] bool wait_closed(double timeout_s);

 private:
  int fd_{-1};
  std::array<std::uint8_t, 4096> buf_{};
  std::size_t begin_{0};
  std::size_t end_{0};
};

class QemuProcess {
 public:
  // Starts argv[0] with its arguments; its standard output (the target's semihosting
  // console) goes to our standard error, or nowhere when !console.
  QemuProcess(const std::vector<std::string>& argv, bool console);
  QemuProcess(const QemuProcess&) = delete;
  QemuProcess& operator=(const QemuProcess&) = delete;
  ~QemuProcess();  // terminates it if it still runs

  [[nodiscard]] bool running();
  // Its exit status (128 + signal if killed by one); -1 if it did not end within timeout_s
  // (it is then terminated).
  int wait(double timeout_s);

 private:
  void terminate();
  pid_t pid_{-1};
  int status_{-1};
};

// The QEMU command line for a PIL run of `firmware` on `machine`, serial line on `socket`.
[[nodiscard]] std::vector<std::string> qemu_command(const std::string& qemu, const std::string& machine,
                                                    const std::string& firmware, const std::string& socket);

}  // namespace gyro::sil
