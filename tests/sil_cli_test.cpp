// gyro_sil as a user runs it: the executable started with a command line, its exit status,
// its standard error, and what it leaves on disk. Each test works in a scratch directory of
// its own; where the old behaviour destroyed a file, the test shows it untouched (content and
// modification time, set in the past first so that any rewrite would show).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kSource = GYRO_SOURCE_DIR;
const fs::path kExe = GYRO_SIL_EXE;
const fs::path kSample = kSource / "scenarios" / "report_sample.json";
const fs::path kBad = kSource / "tests" / "data" / "bad_scenarios";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

// A file's content and modification time, to show it was not rewritten.
struct Snapshot {
  std::string content;
  timespec mtime{};
  bool operator==(const Snapshot& o) const {
    return content == o.content && mtime.tv_sec == o.mtime.tv_sec && mtime.tv_nsec == o.mtime.tv_nsec;
  }
};

// Sets the file's times to 2001-09-09 so that any rewrite changes them, and snapshots it.
Snapshot age_and_snapshot(const fs::path& p) {
  const timespec times[2] = {{1000000000, 0}, {1000000000, 0}};
  EXPECT_EQ(::utimensat(AT_FDCWD, p.c_str(), times, 0), 0) << p;
  Snapshot s;
  s.content = slurp(p);
  struct stat st {};
  EXPECT_EQ(::stat(p.c_str(), &st), 0);
  s.mtime = st.st_mtim;
  return s;
}

Snapshot snapshot(const fs::path& p) {
  Snapshot s;
  s.content = slurp(p);
  struct stat st {};
  EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
  s.mtime = st.st_mtim;
  return s;
}

// Every entry of a directory tree (paths relative to it), sorted.
// (Entries may come and go while a child runs: errors end the listing, they do not throw.)
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    out.push_back(it->path().lexically_relative(dir).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool has_temporary(const fs::path& dir) {
  const std::vector<std::string> l = listing(dir);
  return std::any_of(l.begin(), l.end(), [](const std::string& n) {
    const std::string name = fs::path(n).filename().string();
    return name.size() > 4 && name.front() == '.' && name.substr(name.size() - 4) == ".tmp";
  });
}

std::size_t lines_in(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

// A scratch directory per test, removed at the end.
class Scratch {
 public:
  Scratch() {
    const testing::TestInfo* t = testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "sil_cli_" + std::to_string(::getpid()) + "_" + t->test_suite_name() + "_" + t->name();
    std::replace(name.begin(), name.end(), '/', '_');  // parameterised tests
    dir_ = fs::temp_directory_path() / name;
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "work");
  }
  ~Scratch() {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir_, ec);
  }
  // The user's directory (the child's standard output and error go beside it, not in it).
  [[nodiscard]] fs::path work() const { return dir_ / "work"; }
  [[nodiscard]] fs::path root() const { return dir_; }
  fs::path scenario(const std::string& name = "s.json") const {  // NOLINT(modernize-use-nodiscard)
    fs::copy_file(kSample, work() / name, fs::copy_options::overwrite_existing);
    return work() / name;
  }

 private:
  fs::path dir_;
};

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

struct Options {
  std::vector<std::pair<std::string, std::string>> env;
  std::optional<rlim_t> file_size_limit;  // RLIMIT_FSIZE: writes past it fail with EFBIG
  std::optional<rlim_t> memory_limit;     // RLIMIT_AS: allocations past it fail
  bool as_nobody{false};                  // when run by root, gyro_sil runs as nobody (65534)
  std::optional<fs::path> stdout_append;  // the child's standard output, opened O_APPEND
  // The name gyro_sil once used for its CSV copy with -o - and --plot, $TMPDIR/gyro_sil_PID.csv,
  // made a symbolic link to this file before gyro_sil starts (the child knows its PID).
  std::optional<fs::path> link_old_temporary_to;
};

struct Child {
  pid_t pid{0};
  fs::path out, err;
};

struct Result {
  pid_t pid{0};
  int exit_status{-1};  // -1 if killed by a signal
  int signal{0};
  std::string out, err;
};

Child start(const Scratch& s, const std::vector<std::string>& args, const Options& o = {}) {
  static int n = 0;
  Child c;
  c.out = s.root() / ("stdout_" + std::to_string(n));
  c.err = s.root() / ("stderr_" + std::to_string(n++));
  std::vector<std::string> argv_s = {kExe.string()};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  c.pid = ::fork();
  if (c.pid == 0) {
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) std::signal(sig, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    for (const auto& [k, v] : o.env) ::setenv(k.c_str(), v.c_str(), 1);
    if (o.link_old_temporary_to) {
      const std::string link = std::string(std::getenv("TMPDIR")) + "/gyro_sil_" + std::to_string(::getpid()) + ".csv";
      ::symlink(o.link_old_temporary_to->c_str(), link.c_str());
    }
    if (o.file_size_limit) {
      std::signal(SIGXFSZ, SIG_IGN);  // the write fails with EFBIG instead
      const rlimit lim{*o.file_size_limit, *o.file_size_limit};
      ::setrlimit(RLIMIT_FSIZE, &lim);
    }
    if (o.memory_limit && !kAddressSanitizer) {  // ASan reserves terabytes of shadow up front
      const rlimit lim{*o.memory_limit, *o.memory_limit};
      ::setrlimit(RLIMIT_AS, &lim);
    }
    const int out = o.stdout_append ? ::open(o.stdout_append->c_str(), O_WRONLY | O_APPEND)
                                    : ::open(c.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(c.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(out, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    if (o.as_nobody && ::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(126);
    ::chdir(s.work().c_str());
    std::vector<char*> argv;
    for (std::string& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return c;
}

Result finish(const Child& c) {
  int status = 0;
  while (::waitpid(c.pid, &status, 0) < 0 && errno == EINTR) {
  }
  Result r;
  r.pid = c.pid;
  if (WIFEXITED(status)) r.exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  r.out = slurp(c.out);
  r.err = slurp(c.err);
  return r;
}

Result run(const Scratch& s, const std::vector<std::string>& args, const Options& o = {}) {
  return finish(start(s, args, o));
}

// Waits (up to 20 s) for `ready`.
template <typename Pred>
bool wait_until(Pred ready) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < end) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// The report's sample, `ticks` long.
void write_long_scenario(const fs::path& p, std::uint64_t ticks) {
  json d = json::parse(slurp(kSample));
  d["run"]["ticks"] = ticks;
  spit(p, d.dump(2));
}

// A gnuplot that does `body` (a shell script), for $GNUPLOT.
fs::path fake_gnuplot(const Scratch& s, const std::string& body) {
  const fs::path p = s.root() / "gnuplot";
  spit(p, "#!/bin/sh\n" + body + "\n");
  fs::permissions(p, fs::perms::owner_all);
  return p;
}

bool process_gone(pid_t pid) {
  // Gone, or a zombie waiting for whoever adopted it.
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  if (!stat) return true;
  std::string line;
  std::getline(stat, line);
  const std::size_t close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'Z';
}

// ---------------------------------------------------------------------------------------
// Output paths

TEST(SilCliOutputs, GivenTheScenarioAsTheCsvOrThePlotWhenRunThenRefusedAndTheScenarioIsUntouched) {
  Scratch s;
  const fs::path scen = s.scenario();
  const Snapshot before = age_and_snapshot(scen);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"s.json", "-o", "s.json"}, {"s.json", "-o", "a.csv", "--plot", "s.json"},
        {"s.json", "-o", "./sub/../s.json"}, {"s.json", "-o", (s.work() / "s.json").string()}}) {
    SCOPED_TRACE(args[2] + " " + args.back());
    const Result r = run(s, args);
    EXPECT_EQ(r.exit_status, 2) << r.err;
    EXPECT_NE(r.err.find("is the scenario file"), std::string::npos) << r.err;
    EXPECT_EQ(lines_in(r.err), 1u) << r.err;
    EXPECT_TRUE(snapshot(scen) == before);
    EXPECT_FALSE(fs::exists(s.work() / "a.csv"));
    EXPECT_FALSE(fs::exists(s.work() / "sub"));
  }
}

TEST(SilCliOutputs, GivenALinkToTheScenarioAsTheOutputWhenRunThenRefusedByIdentity) {
  Scratch s;
  const fs::path scen = s.scenario();
  const Snapshot before = age_and_snapshot(scen);
  fs::create_symlink("s.json", s.work() / "soft.csv");
  fs::create_hard_link(scen, s.work() / "hard.csv");
  for (const char* out : {"soft.csv", "hard.csv"}) {
    SCOPED_TRACE(out);
    const Result csv = run(s, {"s.json", "-o", out});
    EXPECT_EQ(csv.exit_status, 2) << csv.err;
    EXPECT_NE(csv.err.find("is the scenario file"), std::string::npos) << csv.err;
    const Result png = run(s, {"s.json", "-o", "a.csv", "--plot", out});
    EXPECT_EQ(png.exit_status, 2) << png.err;
    EXPECT_TRUE(snapshot(scen) == before);
  }
  EXPECT_TRUE(fs::is_symlink(s.work() / "soft.csv"));
}

TEST(SilCliOutputs, GivenStandardOutputOpenOnTheScenarioWhenRunThenRefusedAndTheScenarioIsUntouched) {
  Scratch s;
  const fs::path scen = s.scenario();
  const Snapshot before = age_and_snapshot(scen);
  Options o;
  o.stdout_append = scen;  // gyro_sil s.json >> s.json
  const Result r = run(s, {"s.json"}, o);
  EXPECT_EQ(r.exit_status, 2) << r.err;
  EXPECT_NE(r.err.find("standard output is the scenario file"), std::string::npos) << r.err;
  EXPECT_TRUE(snapshot(scen) == before);
}

TEST(SilCliOutputs, GivenThePlotAsTheCsvWhenRunThenRefusedAndTheCsvIsUntouched) {
  Scratch s;
  s.scenario();
  spit(s.work() / "a.csv", "an earlier run\n");
  const Snapshot before = age_and_snapshot(s.work() / "a.csv");
  for (const char* png : {"a.csv", "./a.csv", "new/../a.csv"}) {
    SCOPED_TRACE(png);
    const Result r = run(s, {"s.json", "-o", "a.csv", "--plot", png});
    EXPECT_EQ(r.exit_status, 2) << r.err;
    EXPECT_NE(r.err.find("is the same file as -o"), std::string::npos) << r.err;
    EXPECT_TRUE(snapshot(s.work() / "a.csv") == before);  // not a PNG where the CSV was
  }
  // Neither exists yet: the same by spelling.
  const Result r = run(s, {"s.json", "-o", "b.csv", "--plot", "dir/../b.csv"});
  EXPECT_EQ(r.exit_status, 2) << r.err;
  EXPECT_FALSE(fs::exists(s.work() / "b.csv"));
  EXPECT_FALSE(fs::exists(s.work() / "dir"));
}

TEST(SilCliOutputs, GivenADirectoryAsAnOutputWhenRunThenRefusedAndTheDirectoryIsKept) {
  Scratch s;
  s.scenario();
  fs::create_directory(s.work() / "empty");
  fs::create_directory(s.work() / "full");
  spit(s.work() / "full" / "f", "x");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"s.json", "-o", "a.csv", "--plot", "empty"}, {"s.json", "-o", "a.csv", "--plot", "full"},
        {"s.json", "-o", "empty"}, {"s.json", "-o", "new/"}, {"s.json", "-o", "a.csv", "--plot", "empty/.."}}) {
    SCOPED_TRACE(args.back());
    const Result r = run(s, args);
    EXPECT_EQ(r.exit_status, 2) << r.err;
    EXPECT_NE(r.err.find("directory"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_directory(s.work() / "empty"));
    EXPECT_EQ(slurp(s.work() / "full" / "f"), "x");
    EXPECT_FALSE(fs::exists(s.work() / "a.csv"));
    EXPECT_FALSE(fs::exists(s.work() / "new"));
  }
}

// A FIFO of the test's own stands for a device: were a check to regress, no system file (such
// as /dev/null) could be harmed.
TEST(SilCliOutputs, GivenAFifoAsAnOutputThenTheCsvIsWrittenIntoItAndThePlotIsRefused) {
  Scratch s;
  s.scenario();
  const Result ref = run(s, {"s.json", "-q", "-o", "ref.csv"});
  ASSERT_EQ(ref.exit_status, 0) << ref.err;
  ASSERT_EQ(::mkfifo((s.work() / "pipe").c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = slurp(s.work() / "pipe"); });
  const Result csv = run(s, {"s.json", "-q", "-o", "pipe"});
  reader.join();
  EXPECT_EQ(csv.exit_status, 0) << csv.err;
  EXPECT_TRUE(received == slurp(s.work() / "ref.csv"));
  EXPECT_EQ(fs::status(s.work() / "pipe").type(), fs::file_type::fifo);
  const Result png = run(s, {"s.json", "-o", "a.csv", "--plot", "pipe"});
  EXPECT_EQ(png.exit_status, 2) << png.err;
  EXPECT_NE(png.err.find("not a regular file"), std::string::npos) << png.err;
  EXPECT_EQ(fs::status(s.work() / "pipe").type(), fs::file_type::fifo);
  EXPECT_FALSE(fs::exists(s.work() / "a.csv"));
}

TEST(SilCliOutputs, GivenAnExistingOutputWhenRunThenReplacedWholeWithItsPermissionsAndThroughItsLink) {
  Scratch s;
  s.scenario();
  const Result fresh = run(s, {"s.json", "-o", "ref.csv"});
  ASSERT_EQ(fresh.exit_status, 0) << fresh.err;
  spit(s.work() / "old.csv", "an earlier run\n");
  fs::permissions(s.work() / "old.csv", fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  fs::create_symlink("old.csv", s.work() / "latest.csv");
  const Result r = run(s, {"s.json", "-o", "latest.csv"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(s.work() / "latest.csv"));  // the link stays, its target is replaced
  EXPECT_EQ(slurp(s.work() / "old.csv"), slurp(s.work() / "ref.csv"));
  EXPECT_EQ(fs::status(s.work() / "old.csv").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_FALSE(has_temporary(s.work()));
}

TEST(SilCliOutputs, GivenCsvOnStandardOutputAndAPlotThenTheCsvIsTheSameAndNoTemporaryIsLeft) {
  Scratch s;
  s.scenario();
  const fs::path tmp = s.root() / "tmp";
  fs::create_directory(tmp);
  spit(tmp / "gyro_sil_csv_existing", "someone else's\n");
  const fs::path victim = s.root() / "victim";
  spit(victim, "not to be overwritten\n");
  const Snapshot victim_before = age_and_snapshot(victim);
  Options o;
  o.env = {{"TMPDIR", tmp.string()}};
  o.link_old_temporary_to = victim;  // a symbolic link planted at the old, predictable name
  const Result file = run(s, {"s.json", "-o", "ref.csv"});
  ASSERT_EQ(file.exit_status, 0) << file.err;
  const Result r = run(s, {"s.json", "--plot", "p.png"}, o);
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(r.out == slurp(s.work() / "ref.csv"));
  EXPECT_GT(fs::file_size(s.work() / "p.png"), 0u);
  // Its private copy is gone; the planted link was not followed.
  std::vector<std::string> left = listing(tmp);
  ASSERT_EQ(left.size(), 2u);
  EXPECT_EQ(left[0], "gyro_sil_" + std::to_string(r.pid) + ".csv");
  EXPECT_EQ(left[1], "gyro_sil_csv_existing");
  EXPECT_EQ(slurp(tmp / "gyro_sil_csv_existing"), "someone else's\n");
  EXPECT_TRUE(snapshot(victim) == victim_before);
  EXPECT_FALSE(has_temporary(s.work()));
}

TEST(SilCliOutputs, GivenOutputsInMissingDirectoriesThenCreatedOnSuccessOnly) {
  Scratch s;
  s.scenario();
  const Result ok = run(s, {"s.json", "-o", "out/a/b.csv"});
  EXPECT_EQ(ok.exit_status, 0) << ok.err;
  EXPECT_TRUE(fs::is_regular_file(s.work() / "out" / "a" / "b.csv"));
  // A run that fails writing (a file size limit) leaves no directory and no temporary behind.
  Options o;
  o.file_size_limit = 100000;
  const Result fail = run(s, {"s.json", "-q", "-o", "new/deeper/c.csv"}, o);
  EXPECT_EQ(fail.exit_status, 1) << fail.err;
  EXPECT_FALSE(fs::exists(s.work() / "new"));
}

// ---------------------------------------------------------------------------------------
// Failures and signals leave nothing partial

TEST(SilCliFailures, GivenAWriteThatFailsMidRunThenTheExistingCsvIsUntouchedAndOneLineSaysSoEvenQuiet) {
  Scratch s;
  s.scenario();
  spit(s.work() / "a.csv", "an earlier run\n");
  const Snapshot before = age_and_snapshot(s.work() / "a.csv");
  Options o;
  o.file_size_limit = 100000;  // the CSV is 411,461 bytes
  const Result r = run(s, {"s.json", "-q", "-o", "a.csv"}, o);
  EXPECT_EQ(r.exit_status, 1) << r.err;
  EXPECT_EQ(lines_in(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("run failed: writing the CSV failed"), std::string::npos) << r.err;
  EXPECT_TRUE(snapshot(s.work() / "a.csv") == before);
  EXPECT_FALSE(has_temporary(s.work()));
}

TEST(SilCliFailures, GivenAFailingGnuplotThenTheCsvIsWrittenTheOldPlotIsKeptAndOneLineSaysSo) {
  Scratch s;
  s.scenario();
  spit(s.work() / "p.png", "an earlier plot");
  const Snapshot before = age_and_snapshot(s.work() / "p.png");
  Options o;
  o.env = {{"GNUPLOT", fake_gnuplot(s, "exit 1").string()}};
  const Result r = run(s, {"s.json", "-q", "-o", "a.csv", "--plot", "p.png"}, o);
  EXPECT_EQ(r.exit_status, 3) << r.err;
  EXPECT_EQ(lines_in(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("plot failed"), std::string::npos) << r.err;
  EXPECT_GT(fs::file_size(s.work() / "a.csv"), 400000u);
  EXPECT_TRUE(snapshot(s.work() / "p.png") == before);
  EXPECT_FALSE(has_temporary(s.work()));
}

TEST(SilCliFailures, GivenAGnuplotThatHangsThenItIsStoppedAfterTheTimeLimit) {
  Scratch s;
  s.scenario();
  spit(s.work() / "p.png", "an earlier plot");
  const Snapshot before = age_and_snapshot(s.work() / "p.png");
  const fs::path pid_file = s.root() / "gnuplot.pid";
  Options o;
  o.env = {{"GNUPLOT", fake_gnuplot(s, "echo $$ > '" + pid_file.string() + "'; exec sleep 60").string()}};
  const auto t0 = std::chrono::steady_clock::now();
  const Result r = run(s, {"s.json", "-o", "a.csv", "--plot", "p.png", "--plot-timeout", "1"}, o);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.exit_status, 3) << r.err;
  EXPECT_NE(r.err.find("did not finish within 1 s"), std::string::npos) << r.err;
  EXPECT_LT(took, 30.0);  // not the 60 s of the hung gnuplot
  ASSERT_TRUE(fs::exists(pid_file));
  const pid_t gnuplot = std::stoi(slurp(pid_file));
  EXPECT_TRUE(wait_until([&] { return process_gone(gnuplot); }));
  EXPECT_TRUE(snapshot(s.work() / "p.png") == before);
  EXPECT_FALSE(has_temporary(s.work()));
}

class SilCliSignals : public testing::TestWithParam<int> {};

TEST_P(SilCliSignals, GivenASignalMidRunThenTheTemporaryAndCreatedDirectoriesAreRemovedAndTheOldCsvIsKept) {
  const int sig = GetParam();
  Scratch s;
  write_long_scenario(s.work() / "long.json", 1000000);  // several seconds
  spit(s.work() / "a.csv", "an earlier run\n");
  const Snapshot before = age_and_snapshot(s.work() / "a.csv");
  for (const char* out : {"a.csv", "new/dir/b.csv"}) {
    SCOPED_TRACE(out);
    const Child c = start(s, {"long.json", "-q", "-o", out});
    ASSERT_TRUE(wait_until([&] { return has_temporary(s.work()); }));
    ::kill(c.pid, sig);
    const Result r = finish(c);
    EXPECT_EQ(r.signal, sig) << r.err;
    EXPECT_FALSE(has_temporary(s.work()));
    EXPECT_TRUE(snapshot(s.work() / "a.csv") == before);
    EXPECT_FALSE(fs::exists(s.work() / "new"));
  }
}

INSTANTIATE_TEST_SUITE_P(IntTermHup, SilCliSignals, testing::Values(SIGINT, SIGTERM, SIGHUP));

TEST(SilCliFailures, GivenASignalWhileGnuplotRunsThenGnuplotIsKilledAndNothingIsLeft) {
  Scratch s;
  s.scenario();
  spit(s.work() / "a.csv", "an earlier run\n");
  const Snapshot before = age_and_snapshot(s.work() / "a.csv");
  const fs::path pid_file = s.root() / "gnuplot.pid";
  Options o;
  o.env = {{"GNUPLOT", fake_gnuplot(s, "echo $$ > '" + pid_file.string() + "'; exec sleep 60").string()}};
  const Child c = start(s, {"s.json", "-o", "a.csv", "--plot", "new/p.png"}, o);
  ASSERT_TRUE(wait_until([&] { return fs::exists(pid_file) && fs::file_size(pid_file) > 0; }));
  ::kill(c.pid, SIGTERM);
  const Result r = finish(c);
  EXPECT_EQ(r.signal, SIGTERM) << r.err;
  const pid_t gnuplot = std::stoi(slurp(pid_file));
  EXPECT_TRUE(wait_until([&] { return process_gone(gnuplot); }));
  EXPECT_TRUE(snapshot(s.work() / "a.csv") == before);  // the CSV is committed only after the plot
  EXPECT_FALSE(has_temporary(s.work()));
  EXPECT_FALSE(fs::exists(s.work() / "new"));
}

// ---------------------------------------------------------------------------------------
// Resources, refused up front

TEST(SilCliResources, GivenAHundredMillionTicksThenRefusedUpFrontNamingTheLengthAndTheSize) {
  Scratch s;
  write_long_scenario(s.work() / "huge.json", 100000000);
  Options o;
  o.file_size_limit = 50u << 20;  // were the refusal to regress, fail at 50 MB rather than fill the disk
  const Result r = run(s, {"huge.json", "-o", "a.csv"}, o);
  EXPECT_EQ(r.exit_status, 2) << r.err;
  EXPECT_EQ(lines_in(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("huge.json: run.ticks: the CSV could take up to"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-output-bytes"), std::string::npos) << r.err;
  EXPECT_EQ(listing(s.work()), std::vector<std::string>{"huge.json"});
}

TEST(SilCliResources, GivenTheOutputLimitRaisedThenTheSameRunGoes) {
  Scratch s;
  write_long_scenario(s.work() / "l.json", 10000);  // about 5 MB of CSV
  const Result refused = run(s, {"l.json", "-o", "a.csv", "--max-output-bytes", "1MB"});
  EXPECT_EQ(refused.exit_status, 2) << refused.err;
  EXPECT_FALSE(fs::exists(s.work() / "a.csv"));
  Options o;
  o.file_size_limit = 50u << 20;
  const Result raised = run(s, {"l.json", "-o", "a.csv", "--max-output-bytes", "10MiB"}, o);
  EXPECT_EQ(raised.exit_status, 0) << raised.err;
  EXPECT_GT(fs::file_size(s.work() / "a.csv"), 4000000u);
  const Result bad = run(s, {"l.json", "--max-output-bytes", "0"});
  EXPECT_EQ(bad.exit_status, 2) << bad.err;
}

TEST(SilCliResources, GivenAnEndlessOrHugeScenarioFileThenRefusedWithoutReadingItAll) {
  Scratch s;
  Options o;
  o.memory_limit = 512u << 20;  // were reading to regress, fail soon rather than exhaust the machine
  const Result zero = run(s, {"/dev/zero", "-o", "a.csv"}, o);
  EXPECT_EQ(zero.exit_status, 2) << zero.err;
  EXPECT_NE(zero.err.find("/dev/zero: (file): gave more than the limit of 1048576 bytes"), std::string::npos)
      << zero.err;
  {
    std::ofstream big(s.work() / "big.json", std::ios::binary);
    big << '{';
  }
  fs::resize_file(s.work() / "big.json", 100u << 20);  // 100 MB (sparse)
  const Result large = run(s, {"big.json", "-o", "a.csv"}, o);
  EXPECT_EQ(large.exit_status, 2) << large.err;
  EXPECT_NE(large.err.find("(file): the file has 104857600 bytes, more than the limit"), std::string::npos)
      << large.err;
  EXPECT_FALSE(fs::exists(s.work() / "a.csv"));
}

TEST(SilCliResources, GivenADirectoryOrAMissingFileAsTheScenarioThenReportedAsSuch) {
  Scratch s;
  fs::create_directory(s.work() / "d.json");
  const Result dir = run(s, {"d.json"});
  EXPECT_EQ(dir.exit_status, 2) << dir.err;
  EXPECT_NE(dir.err.find("d.json: (file): is a directory, not a scenario file"), std::string::npos) << dir.err;
  const Result missing = run(s, {"missing.json"});
  EXPECT_EQ(missing.exit_status, 2) << missing.err;
  EXPECT_NE(missing.err.find("missing.json: (file): cannot open the file for reading: No such file or directory"),
            std::string::npos)
      << missing.err;
}

TEST(SilCliResources, GivenAnUnreadableFileAsTheScenarioThenReportedAsSuch) {
  Scratch s;
  s.scenario("locked.json");
  fs::permissions(s.work() / "locked.json", fs::perms::none);
  Options o;
  o.as_nobody = true;  // root would read it
  const Result locked = run(s, {"locked.json"}, o);
  EXPECT_EQ(locked.exit_status, 2) << locked.err;
  EXPECT_NE(locked.err.find("Permission denied"), std::string::npos) << locked.err;
}

// ---------------------------------------------------------------------------------------
// Option values: checked whole, before anything runs; no bound switched off by a number

bool has_control_characters(const std::string& s) {
  return std::any_of(s.begin(), s.end(), [](char c) {
    const auto b = static_cast<unsigned char>(c);
    return (b < 0x20 && b != '\n') || b == 0x7f;
  });
}

// A refusal of the command line: exit status 2, one line naming `shown` (the option and its
// value as echoed), no control character, nothing written in the user's directory.
void expect_refused(const Scratch& s, const std::vector<std::string>& args, const std::string& shown,
                    const std::string& bound = "") {
  std::string trace;
  for (const std::string& a : args) trace += "[" + a + "] ";
  SCOPED_TRACE(trace);
  Options o;
  o.file_size_limit = 50u << 20;  // were a refusal to regress into a run, stop it at 50 MB
  const Result r = run(s, args, o);
  EXPECT_EQ(r.exit_status, 2) << r.err;
  EXPECT_EQ(lines_in(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("bad command line: " + shown), std::string::npos) << r.err;
  if (!bound.empty()) {
    EXPECT_NE(r.err.find(bound), std::string::npos) << r.err;
  }
  EXPECT_FALSE(has_control_characters(r.err)) << r.err;
  EXPECT_FALSE(fs::exists(s.work() / "a.csv"));
  EXPECT_FALSE(fs::exists(s.work() / "p.png"));
}

TEST(SilCliOptions, GivenANegativeOrMalformedOutputBoundThenRefusedNamingTheOptionAndTheValue) {
  Scratch s;
  // 100 million ticks: about 58 GB of CSV. "-1" once wrapped to 2^64 - 1 and started it.
  write_long_scenario(s.work() / "huge.json", 100000000);
  for (const char* v : {"-1", "-1GiB", "", "abc", "1.5MB", "0", "0GiB", "2xB", "99999999999999999999", "17EiB",
                        " 1MB", "+5"}) {
    expect_refused(s, {"huge.json", "-q", "-o", "a.csv", "--max-output-bytes", v},
                   "--max-output-bytes \"" + std::string(v) + "\": ");
  }
  // The largest size a number can give is still a bound, and the units are those of before.
  const Result huge = run(s, {"huge.json", "-q", "-o", "a.csv", "--max-output-bytes", "16EiB"});
  EXPECT_EQ(huge.exit_status, 2) << huge.err;
  write_long_scenario(s.work() / "l.json", 10000);  // about 5 MB of CSV
  for (const char* v : {"1MB", "1 MB", "4000kB", "1mib", "5000000B"}) {
    const Result r = run(s, {"l.json", "-q", "-o", "a.csv", "--max-output-bytes", v});
    EXPECT_EQ(r.exit_status, 2) << v << ": " << r.err;
    EXPECT_NE(r.err.find("more than the limit of"), std::string::npos) << r.err;
  }
  for (const char* v : {"10MB", "10 MiB", "1gb", "1EiB", "18446744073709551615"}) {
    const Result r = run(s, {"l.json", "-q", "-o", "a.csv", "--max-output-bytes", v});
    EXPECT_EQ(r.exit_status, 0) << v << ": " << r.err;
  }
}

TEST(SilCliOptions, GivenANonFiniteNegativeZeroEmptyOrHugeTimeoutThenRefusedNamingOptionValueAndBound) {
  Scratch s;
  s.scenario();
  const char* bad[] = {"nan", "NaN", "-nan", "inf", "-inf", "infinity", "-1", "0", "-0", "", "1e400",
                       "1e-400", "5s", " 5", "abc"};
  for (const char* v : bad) {
    expect_refused(s, {"s.json", "-q", "-o", "a.csv", "--plot", "p.png", "--plot-timeout", v},
                   "--plot-timeout \"" + std::string(v) + "\": ", "<= 86400");
    // Refused before the socket is even looked at (there is none).
    expect_refused(s, {"s.json", "-q", "-o", "a.csv", "--pil", (s.root() / "none.sock").string(), "--pil-timeout", v},
                   "--pil-timeout \"" + std::string(v) + "\": ", "<= 3600");
  }
  expect_refused(s, {"s.json", "-q", "-o", "a.csv", "--plot-timeout", "86401"}, "--plot-timeout \"86401\": ",
                 "more than the limit of 86400 s");
  expect_refused(s, {"s.json", "-q", "-o", "a.csv", "--pil", "x.sock", "--pil-timeout", "3600.5"},
                 "--pil-timeout \"3600.5\": ", "more than the limit of 3600 s");
  const Result ok = run(s, {"s.json", "-q", "-o", "a.csv", "--plot", "p.png", "--plot-timeout", "86400"});
  EXPECT_EQ(ok.exit_status, 0) << ok.err;
  EXPECT_TRUE(fs::exists(s.work() / "p.png"));
}

TEST(SilCliOptions, GivenAnEmptyValueOfAnyStringOptionThenRefusedNamingTheOption) {
  Scratch s;
  s.scenario();
  const std::string sock = (s.root() / "none.sock").string();
  struct Case {
    std::vector<std::string> args;
    std::string shown;
  };
  const Case cases[] = {
      {{"", "-o", "a.csv"}, "scenario \"\": empty"},
      {{"s.json", "-o", ""}, "--output \"\": empty"},
      {{"s.json", "--output", ""}, "--output \"\": empty"},
      {{"s.json", "-o", "a.csv", "--plot", ""}, "--plot \"\": empty"},
      {{"s.json", "-o", "a.csv", "--pil", ""}, "--pil \"\": empty"},
      {{"s.json", "-o", "a.csv", "--pil", sock, "--pil-firmware", ""}, "--pil-firmware \"\": empty"},
      {{"s.json", "-o", "a.csv", "--pil", sock, "--pil-machine", ""}, "--pil-machine \"\": empty"},
      {{"s.json", "-o", "a.csv", "--pil", sock, "--pil-fault", ""}, "--pil-fault \"\": empty"},
      {{"s.json", "-o", "a.csv", "--precision", ""}, "--precision"},
  };
  for (const Case& c : cases) expect_refused(s, c.args, c.shown);
}

TEST(SilCliOptions, GivenControlCharactersInAnOptionValueThenTheEchoIsEscaped) {
  Scratch s;
  s.scenario();
  const std::string sock = (s.root() / "none.sock").string();
  // The wire fault's kind and its ticks are echoed twice: the option's value and the reason.
  expect_refused(s, {"s.json", "-o", "a.csv", "--pil", sock, "--pil-fault", "\x1b[31mcrc@1"},
                 "--pil-fault \"\\x1b[31mcrc@1\": unknown wire fault \"\\x1b[31mcrc\"");
  expect_refused(s, {"s.json", "-o", "a.csv", "--pil", sock, "--pil-fault", "crc@1\x1b]0;x\x07"},
                 "--pil-fault \"crc@1\\x1b]0;x\\x07\": bad tick or tick count in \"crc@1\\x1b]0;x\\x07\"");
  expect_refused(s, {"s.json", "-o", "a.csv", "--max-output-bytes", "1\x1b[2J"},
                 "--max-output-bytes \"1\\x1b[2J\": unknown unit \"\\x1b[2J\"");
  expect_refused(s, {"s.json", "-o", "a.csv", "--plot-timeout", "\r5"}, "--plot-timeout \"\\r5\": not a number");
  expect_refused(s, {"s.json", "-o", "a.csv", "--ticks", "\x1b[31m"}, "--ticks");
}

// ---------------------------------------------------------------------------------------
// Validation: the scenarios that passed and then failed on their first tick

TEST(SilCliValidation, GivenEachScenarioThatUsedToFailOnItsFirstTickThenRefusedNamingTheFieldAndNothingWritten) {
  struct Case {
    const char* file;
    const char* field;
  };
  const Case cases[] = {
      {"overflow_spin.json", "gyro.rotor.spin_hz"},
      {"overflow_inertia.json", "gyro.rotor.pitch_inertia"},
      {"overflow_torquer_scale.json", "gyro.torquer.scale_factor"},
      {"overflow_pickoff_lsb.json", "gyro.pickoff.lsb_rad"},
      {"overflow_body_rate.json", "body.rate_rad_s[0]"},
      {"overflow_float_slew.json", "guidance.schedule[0].slew_rate_rad_s[0]"},
      {"overflow_component_rotor.json", "component.pitch_inertia"},
      {"duplicate_key.json", "gyro.rotor.friction"},
      {"integer_wraps.json", "gyro.faults[0].axis"},
  };
  Scratch s;
  spit(s.work() / "a.csv", "an earlier run\n");
  const Snapshot before = age_and_snapshot(s.work() / "a.csv");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const Result r = run(s, {(kBad / c.file).string(), "-q", "-o", "a.csv", "--plot", "p.png"});
    EXPECT_EQ(r.exit_status, 2) << r.err;
    EXPECT_EQ(lines_in(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(std::string(c.file) + ": " + c.field + ": "), std::string::npos) << r.err;
    EXPECT_TRUE(snapshot(s.work() / "a.csv") == before);
    EXPECT_EQ(listing(s.work()), std::vector<std::string>{"a.csv"});
  }
}

TEST(SilCliValidation, GivenControlCharactersInAKeyAndInTheFileNameThenEveryMessageIsEscaped) {
  Scratch s;
  const std::string name = "evil\x1b]0;pwned\x07\x1b[2J.json";
  fs::copy_file(kBad / "control_characters_in_key.json", s.work() / name);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{name, "-o", "a.csv"}, {"missing\x1b[31m.json"}, {"--precision", "\x1b[31m", name},
        {(kBad / "control_characters_in_key.json").string()}}) {
    const Result r = run(s, args);
    EXPECT_EQ(r.exit_status, 2) << r.err;
    ASSERT_FALSE(r.err.empty());
    const std::string body = r.err.substr(0, r.err.size() - 1);
    EXPECT_EQ(r.err.back(), '\n');
    EXPECT_TRUE(std::none_of(body.begin(), body.end(), [](char c) {
      const auto b = static_cast<unsigned char>(c);
      return b < 0x20 || b == 0x7f;
    })) << r.err;
  }
  const Result key = run(s, {(kBad / "control_characters_in_key.json").string()});
  EXPECT_NE(key.err.find("body[\"rate\\u001b[2J\\u001b[31m\"]: unknown key"), std::string::npos) << key.err;
  const Result file = run(s, {name});
  EXPECT_NE(file.err.find("evil\\x1b]0;pwned\\x07\\x1b[2J.json"), std::string::npos) << file.err;
}

TEST(SilCliValidation, GivenTheSampleThenItStillRunsAndQuietPrintsNothing) {
  Scratch s;
  s.scenario();
  const Result r = run(s, {"s.json", "-q", "-o", "a.csv", "--plot", "p.png"});
  EXPECT_EQ(r.exit_status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(listing(s.work()), (std::vector<std::string>{"a.csv", "p.png", "s.json"}));
}

// ---------------------------------------------------------------------------------------
// --resolved

TEST(SilCliResolved, GivenAScenarioOnABaseThenResolvedWritesItAsFlownAndRunsNothing) {
  Scratch s;
  const Result r = run(s, {(kSource / "scenarios" / "fault_dead_torquer.json").string(), "--resolved", "-o", "r.json"});
  EXPECT_EQ(r.exit_status, 0) << r.err;
  EXPECT_EQ(listing(s.work()), (std::vector<std::string>{"r.json"}));
  const json d = json::parse(slurp(s.work() / "r.json"));
  EXPECT_FALSE(d.contains("base"));
  EXPECT_FALSE(d.contains("example"));
  EXPECT_EQ(d["gyro"]["rotor"]["pitch_inertia"], 2e-5);      // from the seeker example
  EXPECT_EQ(d["gyro"]["torquer"]["max_torque"], 0.05);       // from seeker_slew.json
  EXPECT_EQ(d["gyro"]["faults"][0]["kind"], "dead_torquer");  // its own
}

}  // namespace
