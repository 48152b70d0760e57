// The processes of one gyro_campaign run: one without MPI, or the ranks of `mpirun -np N`.
// Rank 0 reads the inputs, writes the outputs and gathers the rows; the other ranks receive
// the campaign's text from it, run their share of the runs and stream their rows back.
// Only the thread that made the Cluster calls it (MPI_THREAD_FUNNELED). Waits poll with
// short sleeps rather than spin, so a rank waiting on another does not take a core from it.
//
// Built without MPI (no MPI found by CMake), a Cluster is rank 0 of 1.
#pragma once

#include <memory>
#include <string>

namespace gyro::campaign {

class Cluster {
 public:
  Cluster(int& argc, char**& argv);
  ~Cluster();
  Cluster(const Cluster&) = delete;
  Cluster& operator=(const Cluster&) = delete;

  [[nodiscard]] int rank() const noexcept { return rank_; }
  [[nodiscard]] int size() const noexcept { return size_; }
  [[nodiscard]] bool root() const noexcept { return rank_ == 0; }

  // Rank 0's `text` and `status`, on every rank.
  void broadcast(std::string& text, int& status);

  // Not rank 0: sends a batch of rows to rank 0 without waiting for it; `last` ends this
  // rank's stream. flush() waits (sleeping) until every batch has gone.
  void send_rows(std::string rows, bool last);
  void flush();

  // Rank 0: a batch of rows if one has arrived (`last`: its rank has finished).
  [[nodiscard]] bool receive_rows(std::string& rows, bool& last);

  // Ends every rank at once (a failure on one).
  [[noreturn]] void abort(int code);

  // Started by an MPI launcher with several processes although built without MPI: each
  // process would run the whole campaign alone.
  [[nodiscard]] static bool launched_without_mpi();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int rank_{0};
  int size_{1};
};

}  // namespace gyro::campaign
