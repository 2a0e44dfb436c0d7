// `mpirun -n 2 erpt render ...` on this machine (loopback): a render split over processes
// (docs/long-renders.md, "Many machines"). Built only when CMake found MPI (the setup script
// installs Open MPI, so the suite always has these).
#ifdef ERPT_TEST_MPI
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "erpt/image_io.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

namespace fs = std::filesystem;
std::string defaultScene() { return test::sourceDir() + "/scenes/default/scene.xml"; }

// Open MPI as root, on one machine, over TCP on loopback (no shared-memory transport to
// depend on), with more ranks than cores allowed.
std::string mpirun(int ranks) {
  return std::string(ERPT_MPIRUN) + " --allow-run-as-root --oversubscribe --mca btl self,tcp -n " +
         std::to_string(ranks) + " ";
}

test::CommandResult run(const std::string& command) {
  std::string cmd = command + " 2>&1";
  test::CommandResult r{0, ""};
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string render(int ranks, const std::string& args) {
  return (ranks > 0 ? mpirun(ranks) : std::string()) + ERPT_CLI_PATH + " render -q " + defaultScene() + " --threads 1 " + args;
}

bool sameBits(const RgbImage& a, const RgbImage& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

double channelMean(const RgbImage& img) {
  double s = 0;
  for (const Color& c : img.pixels) s += c.x + c.y + c.z;
  return s / (3.0 * double(img.pixels.size()));
}

// Two ranks render passes 0, 2, 4, ... and 1, 3, 5, ...: the path tracer's (and BDPT's) samples are then the
// same as one process's, and only the order of the film's (double) additions differs. ERPT's
// chains have a random stream per rank, and PMC-ER's populations run over each rank's groups
// of passes: their images differ from one process's by noise only.
// Either way the same K and seed give the same image on every run.
TEST(MpiCli, TwoRanksGiveTheSameImageEveryRunAndMatchOneProcess) {
  test::TempDir dir;
  for (const char* integrator : {"path", "erpt", "pmc-er", "bdpt"}) {
    SCOPED_TRACE(integrator);
    const std::string args = std::string(" --width 64 --height 64 --spp 16 --integrator ") + integrator + " -o ";
    const std::string a = dir.file(std::string(integrator) + "-a.exr"), b = dir.file(std::string(integrator) + "-b.exr"),
                      one = dir.file(std::string(integrator) + "-1.exr");
    for (const std::string& out : {a, b}) {
      const test::CommandResult r = run(render(2, args + out));
      ASSERT_EQ(r.exitCode, 0) << r.output;
      EXPECT_NE(r.output.find("rendered by 2 processes"), std::string::npos) << r.output;
    }
    const test::CommandResult r = run(render(0, args + one));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const RgbImage imageA = readImage(a), imageB = readImage(b), single = readImage(one);
    EXPECT_TRUE(sameBits(imageA, imageB));
    double worst = 0;
    for (size_t i = 0; i < single.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(double(imageA.pixels[i][c]) - single.pixels[i][c]) / (single.pixels[i][c] + 1e-3));
    if (std::string(integrator) == "path" || std::string(integrator) == "bdpt") {
      EXPECT_LT(worst, 1e-5);  // the same samples
    } else {
      EXPECT_GT(worst, 1e-3);  // other chains
      EXPECT_NEAR(channelMean(imageA) / channelMean(single), 1.0, 0.03);
    }
  }
}

// ERPT over two processes against one, block by block: twelve renders each (seeds 1-12), 8x8
// blocks, Welch's z from the runs' spread (support/image_stats.h).
TEST(StatisticalErpt, TwoRanksMatchOneProcessBlockByBlock) {
  test::TempDir dir;
  std::vector<RgbImage> two, one;
  for (int seed = 1; seed <= 12; ++seed) {
    // Other seeds for the two sets: with the same seed both would trace the same seed paths
    // (those do not depend on K), and the z-scores of correlated sets would be too small.
    const std::string args = " --width 64 --height 64 --spp 8 --filter box --integrator erpt --seed ";
    const std::string a = dir.file("two.exr"), b = dir.file("one.exr");
    test::CommandResult r = run(render(2, args + std::to_string(1000 + seed) + " -o " + a));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = run(render(0, args + std::to_string(seed) + " -o " + b));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    two.push_back(readImage(a));
    one.push_back(readImage(b));
  }
  const test::BlockZScores z = test::blockZScores(two, one, 8);
  std::printf("erpt 2 ranks vs 1: %zu blocks: mean z^2 %.2f, worst |z| %.2f\n", z.z.size(), z.meanSquare, z.worst);
  EXPECT_LT(z.meanSquare, 2.0);
  EXPECT_LT(z.worst, 4.5);
}

std::vector<pid_t> childrenOf(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) + "/children");
  std::vector<pid_t> out;
  for (pid_t c; in >> c;) out.push_back(c);
  return out;
}

pid_t spawn(const std::string& command, const std::string& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    FILE* f = std::freopen(log.c_str(), "w", stdout);
    (void)f;
    dup2(STDOUT_FILENO, STDERR_FILENO);
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), nullptr);
    _exit(127);
  }
  return pid;
}

int waitFor(pid_t pid, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  return -1;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The ranks' processes (children of mpirun), once both have written their first checkpoint.
std::vector<pid_t> ranksOnceStarted(pid_t mpirunPid, const std::string& checkpoint, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    const std::vector<pid_t> ranks = childrenOf(mpirunPid);
    if (ranks.size() == 2 && fs::exists(checkpoint + ".0") && fs::exists(checkpoint + ".1")) return ranks;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return {};
}

// Checkpoints are per rank (FILE.0, FILE.1): both ranks stopped by SIGTERM write theirs, rank 0
// writes the partial image of all ranks' passes, and `mpirun -n 2 erpt resume FILE` ends with the
// image of an uninterrupted two-rank render, bit for bit.
TEST(MpiCli, PerRankCheckpointsResumeBitIdentically) {
  test::TempDir dir;
  const std::string ckpt = dir.file("r.ckpt"), out = dir.file("r.exr"), log = dir.file("log.txt");
  const std::string args = " --width 128 --height 128 --spp 128 --integrator path --checkpoint " + ckpt +
                           " --checkpoint-every 0 -o ";
  const pid_t job = spawn(render(2, args + out), log);
  const std::vector<pid_t> ranks = ranksOnceStarted(job, ckpt, 120);
  ASSERT_EQ(ranks.size(), 2u) << readText(log);
  for (pid_t r : ranks) kill(r, SIGTERM);
  const int status = waitFor(job, 120);
  EXPECT_NE(status, 0) << readText(log);
  EXPECT_NE(status, -1) << "the job hung";
  const test::CommandResult resumed = run(mpirun(2) + ERPT_CLI_PATH + " resume -q " + ckpt);
  ASSERT_EQ(resumed.exitCode, 0) << readText(log) << resumed.output;
  const std::string whole = dir.file("whole.exr");
  const test::CommandResult r = run(render(2, " --width 128 --height 128 --spp 128 --integrator path -o " + whole));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(sameBits(readImage(out), readImage(whole)));
}

// A rank that dies ends the job with an error, without hanging and without an image.
TEST(MpiCli, ARankThatDiesFailsTheJob) {
  test::TempDir dir;
  const std::string ckpt = dir.file("r.ckpt"), out = dir.file("r.exr"), log = dir.file("log.txt");
  const pid_t job = spawn(render(2, " --width 256 --height 256 --spp 65536 --checkpoint " + ckpt + " --checkpoint-every 0 -o " + out), log);
  const std::vector<pid_t> ranks = ranksOnceStarted(job, ckpt, 120);
  ASSERT_EQ(ranks.size(), 2u) << readText(log);
  kill(ranks[1], SIGKILL);
  const int status = waitFor(job, 120);
  EXPECT_NE(status, -1) << "the job hung: " << readText(log);
  EXPECT_NE(status, 0) << readText(log);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(readText(log).empty());
}

}  // namespace
}  // namespace erpt
#endif
