// What gyro_sil removes if a signal ends it (SIGINT, SIGTERM, SIGHUP, SIGPIPE): its temporary
// files, the directories it created for its outputs, and the plotting child. The handler
// unlinks every registered file, removes the registered directories (newest first; only empty
// ones go), kills the child's process group, then lets the same signal end the process (the
// shell sees 128 + N as usual). It calls only async-signal-safe functions (unlink, rmdir,
// kill, signal, raise), on paths copied into static storage when registered.
#pragma once

#include <signal.h>
#include <sys/types.h>

#include <string>

namespace gyro::sil::signal_cleanup {

// Installs the handlers (once; before the first temporary file exists).
void install();

// Registers a path; returns its slot for forget(). Throws std::runtime_error when the path is
// longer than PATH_MAX or the (fixed, 64-slot) registry is full.
int add_file(const std::string& path);
int add_directory(const std::string& path);

// The path is no longer to be removed (renamed into place, or removed already). A negative
// slot is ignored.
void forget(int slot) noexcept;

// The process group of the running child (0: none).
void set_child(pid_t process_group) noexcept;

// Holds the signals back while it lives: a file created and then registered inside its scope
// cannot be left behind by a signal that arrives in between (it is delivered at the end).
class Deferred {
 public:
  Deferred() noexcept;
  ~Deferred();
  Deferred(const Deferred&) = delete;
  Deferred& operator=(const Deferred&) = delete;

 private:
  sigset_t old_{};
};

}  // namespace gyro::sil::signal_cleanup
