#include "cluster.hpp"

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <string_view>
#include <thread>

#ifdef GYRO_HAVE_MPI
#include <mpi.h>
#endif

namespace gyro::campaign {

#ifdef GYRO_HAVE_MPI

namespace {

constexpr int kTagRows = 1;
constexpr int kTagLast = 2;

void nap() { std::this_thread::sleep_for(std::chrono::milliseconds(1)); }

// Set by the launchers of MPI jobs (Open MPI's mpirun, Hydra and Slurm's PMI, PMIx): without
// one the process is alone, and MPI is not started at all (a singleton MPI_Init costs about a
// second with Open MPI).
bool launched_by_mpi() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MV2_COMM_WORLD_SIZE"}) {
    if (std::getenv(var) != nullptr) return true;
  }
  return false;
}

}  // namespace

struct Cluster::Impl {
  bool started{false};
  struct Pending {
    std::string buffer;
    MPI_Request request{MPI_REQUEST_NULL};
  };
  std::deque<Pending> sends;

  static void wait(MPI_Request& r) {
    int done = 0;
    while (MPI_Test(&r, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && done == 0) nap();
  }
  void progress() {
    while (!sends.empty()) {
      int done = 0;
      MPI_Test(&sends.front().request, &done, MPI_STATUS_IGNORE);
      if (done == 0) break;
      sends.pop_front();
    }
  }
};

Cluster::Cluster(int& argc, char**& argv) : impl_(std::make_unique<Impl>()) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  impl_->started = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Cluster::~Cluster() {
  if (!impl_->started) return;
  flush();
  MPI_Finalize();
}

void Cluster::broadcast(std::string& text, int& status) {
  if (size_ == 1) return;
  std::uint64_t head[2] = {static_cast<std::uint64_t>(status), text.size()};
  MPI_Request r{};
  MPI_Ibcast(head, 2, MPI_UINT64_T, 0, MPI_COMM_WORLD, &r);
  Impl::wait(r);
  status = static_cast<int>(head[0]);
  text.resize(head[1]);
  if (head[1] == 0) return;
  MPI_Ibcast(text.data(), static_cast<int>(head[1]), MPI_CHAR, 0, MPI_COMM_WORLD, &r);
  Impl::wait(r);
}

void Cluster::send_rows(std::string rows, bool last) {
  impl_->sends.push_back({std::move(rows), MPI_REQUEST_NULL});
  Impl::Pending& p = impl_->sends.back();
  MPI_Isend(p.buffer.data(), static_cast<int>(p.buffer.size()), MPI_CHAR, 0, last ? kTagLast : kTagRows,
            MPI_COMM_WORLD, &p.request);
  impl_->progress();
}

void Cluster::flush() {
  while (!impl_->sends.empty()) {
    impl_->progress();
    if (!impl_->sends.empty()) nap();
  }
}

bool Cluster::receive_rows(std::string& rows, bool& last) {
  if (size_ == 1) return false;
  int arrived = 0;
  MPI_Status st{};
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &st);
  if (arrived == 0) return false;
  int count = 0;
  MPI_Get_count(&st, MPI_CHAR, &count);
  rows.resize(static_cast<std::size_t>(count));
  MPI_Request r{};
  MPI_Irecv(rows.data(), count, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, &r);
  Impl::wait(r);
  last = st.MPI_TAG == kTagLast;
  return true;
}

void Cluster::abort(int code) {
  if (impl_->started) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

#else  // one process

struct Cluster::Impl {};

Cluster::Cluster(int& /*argc*/, char**& /*argv*/) {}
Cluster::~Cluster() = default;
void Cluster::broadcast(std::string& /*text*/, int& /*status*/) {}
void Cluster::send_rows(std::string /*rows*/, bool /*last*/) {}
void Cluster::flush() {}
bool Cluster::receive_rows(std::string& /*rows*/, bool& /*last*/) { return false; }
void Cluster::abort(int code) { std::exit(code); }

#endif

bool Cluster::launched_without_mpi() {
#ifdef GYRO_HAVE_MPI
  return false;
#else
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MV2_COMM_WORLD_SIZE", "MPI_LOCALNRANKS"}) {
    const char* v = std::getenv(var);
    if (v != nullptr && std::atoi(v) > 1) return true;
  }
  return false;
#endif
}

}  // namespace gyro::campaign
