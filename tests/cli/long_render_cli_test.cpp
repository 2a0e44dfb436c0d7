// `erpt render` stopped by a signal, `--checkpoint` / `erpt resume`, `--write-partial`, from
// the command line (docs/long-renders.md). No wall-clock limit is asserted: the tests wait for
// files to appear (with generous time-outs that only end a hung run) and check exit codes,
// metadata and images.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>
#include <thread>

#include "erpt/image_io.h"
#include "support/test_support.h"
#include "support/tev_test_server.h"

namespace erpt {
namespace {

namespace fs = std::filesystem;
std::string defaultScene() { return test::sourceDir() + "/scenes/default/scene.xml"; }

// A running `erpt` process, its output to a file.
class CliProcess {
 public:
  CliProcess(const std::vector<std::string>& args, const std::string& log) {
    pid_ = fork();
    if (pid_ == 0) {
      std::vector<char*> argv{const_cast<char*>(ERPT_CLI_PATH)};
      for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      FILE* out = std::freopen(log.c_str(), "w", stderr);
      (void)out;
      execv(ERPT_CLI_PATH, argv.data());
      _exit(127);
    }
  }
  ~CliProcess() {
    if (pid_ > 0 && !done_) kill(pid_, SIGKILL), waitpid(pid_, nullptr, 0);
  }
  void signal(int sig) { kill(pid_, sig); }
  // Exit status (128 + signal for a death by signal), or -1 after `seconds`.
  int wait(double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        done_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return -1;
  }

 private:
  pid_t pid_ = -1;
  bool done_ = false;
};

bool waitForFile(const std::string& path, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (fs::exists(path)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool sameBits(const RgbImage& a, const RgbImage& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

// The sanitizer build renders ~10x slower: the same wall time there takes 8x fewer samples.
#ifdef ERPT_TESTS_SANITIZED
constexpr int kSlowdown = 8;
#else
constexpr int kSlowdown = 1;
#endif

std::vector<std::string> renderArgs(const std::string& scene, const std::string& integrator, int spp,
                                    const std::string& out, const std::string& ckpt) {
  std::vector<std::string> args{"render", "-q", scene, "--width", "128", "--height", "128", "--spp", std::to_string(spp),
                                "--integrator", integrator};
  if (integrator == "erpt")  // options the other integrators refuse
    args.insert(args.end(), {"--mutations-per-pixel", "50", "--chain-length", "20", "--direct-samples", "4"});
  args.insert(args.end(), {"-o", out, "--checkpoint", ckpt, "--checkpoint-every", "0"});
  return args;
}

std::string shellArgs(const std::vector<std::string>& args) {
  std::string joined;
  for (const std::string& a : args) joined += "'" + a + "' ";
  return joined;
}

// Ctrl-C (SIGINT) and SIGTERM: the render stops after its batch, writes the passes it completed
// (or the work ERPT's chains did in the first group) marked partial in the EXR and in the
// summary, and exits 130 / 143. `erpt resume` then
// finishes it (here from another directory and on one thread) with the bit-identical image of
// an uninterrupted render.
TEST(LongRenderCli, ASignalWritesThePartialImageAndResumeFinishesItBitIdentically) {
  for (const auto& [sig, status, integrator, spp] :
       {std::tuple{SIGINT, 130, "path", 128 / kSlowdown}, std::tuple{SIGTERM, 143, "erpt", 32 / kSlowdown}}) {
    SCOPED_TRACE(integrator);
    test::TempDir dir;
    const std::string out = dir.file("r.exr"), ckpt = dir.file("r.ckpt"), log = dir.file("log.txt");
    {
      CliProcess p(renderArgs(defaultScene(), integrator, spp, out, ckpt), log);
      ASSERT_TRUE(waitForFile(ckpt, 300)) << readText(log);  // set-up done; the passes under way
      p.signal(sig);
      ASSERT_EQ(p.wait(300), status) << readText(log);
    }
    const std::string said = readText(log);
    EXPECT_NE(said.find("erpt resume " + ckpt), std::string::npos) << said;
    if (fs::exists(out)) {  // else stopped before its first pass (it says so)
      EXPECT_NE(said.find("PARTIAL image"), std::string::npos) << said;
      const RgbImage partial = readImage(out);
      const std::string* note = partial.attribute("erpt:partial");
      ASSERT_NE(note, nullptr);
      // "17 of 32 samples per pixel", or, for ERPT stopped in its first group, which keeps the
      // chains' work: "41.3% of the render's work (0 of 32 sample passes complete, ...)".
      EXPECT_NE(note->find("of " + std::to_string(spp) + " sample"), std::string::npos) << *note;
      EXPECT_TRUE(fs::exists(dir.file("r.png")));
    } else {
      EXPECT_NE(said.find("before the first sample pass"), std::string::npos) << said;
    }
    test::CommandResult resumed = test::runCli("resume -q --threads 1 " + ckpt);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("resumed after"), std::string::npos) << resumed.output;
    const RgbImage finished = readImage(out);
    EXPECT_EQ(finished.attribute("erpt:partial"), nullptr);
    const std::string again = dir.file("again.exr");
    test::CommandResult whole = test::runCli(shellArgs(renderArgs(defaultScene(), integrator, spp, again, dir.file("b.ckpt"))));
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    EXPECT_TRUE(sameBits(finished, readImage(again)));
  }
}

// A second signal ends the process at once: exit 130, no image. (Two signals sent together
// would arrive as one, so the second goes once the first has been taken. The image is
// 1024x1024 so that finishing the batch and writing the image take longer than that.)
TEST(LongRenderCli, ASecondSignalQuitsWithoutWriting) {
  test::TempDir dir;
  const std::string out = dir.file("r.exr"), ckpt = dir.file("r.ckpt"), log = dir.file("log.txt");
  std::vector<std::string> args = renderArgs(defaultScene(), "path", 1 << 20, out, ckpt);
  args[4] = args[6] = "1024";
  CliProcess p(args, log);
  ASSERT_TRUE(waitForFile(ckpt, 300)) << readText(log);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  p.signal(SIGINT);
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (readText(log).find("stopping after the current batch") == std::string::npos && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  p.signal(SIGINT);
  ASSERT_EQ(p.wait(300), 130) << readText(log);
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(dir.path()))  // no temporary image left behind
    EXPECT_EQ(entry.path().filename().string().find(".r.partial"), std::string::npos) << entry.path();
}

// --write-partial: while the render runs, the output holds the image of the passes done,
// marked as in progress.
TEST(LongRenderCli, WritePartialShowsTheImageSoFar) {
  test::TempDir dir;
  const std::string out = dir.file("r.exr"), log = dir.file("log.txt");
  std::vector<std::string> args = renderArgs(defaultScene(), "path", 1 << 20, out, dir.file("r.ckpt"));
  args.resize(args.size() - 4);  // no checkpoint
  args.insert(args.end(), {"--write-partial", "0.001"});
  CliProcess p(args, log);
  ASSERT_TRUE(waitForFile(out, 300)) << readText(log);
  p.signal(SIGKILL);
  EXPECT_EQ(p.wait(300), 128 + SIGKILL);
  const RgbImage partial = readImage(out);
  const std::string* note = partial.attribute("erpt:partial");
  ASSERT_NE(note, nullptr);
  EXPECT_NE(note->find("in progress"), std::string::npos) << *note;
  double sum = 0;
  for (const Color& c : partial.pixels) sum += c.x + c.y + c.z;
  EXPECT_GT(sum, 0);
}

// A checkpoint of an edited scene is refused; checkpoints need a fixed --spp (not --time).
TEST(LongRenderCli, ResumeRefusesAnEditedSceneAndCheckpointsNeedAFixedSpp) {
  test::TempDir dir;
  const std::string scene = dir.write("s.xml", readText(defaultScene()));
  const std::string ckpt = dir.file("r.ckpt");
  test::CommandResult r = test::runCli(shellArgs(renderArgs(scene, "path", 8, dir.file("r.exr"), ckpt)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  dir.write("s.xml", readText(defaultScene()) + "<!-- edited -->\n");
  test::CommandResult refused = test::runCli("resume -q " + ckpt);
  EXPECT_EQ(refused.exitCode, 1) << refused.output;
  EXPECT_NE(refused.output.find(ckpt), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("another scene"), std::string::npos) << refused.output;
  test::CommandResult timed = test::runCli("render -q " + scene + " --time 1 --checkpoint " + dir.file("t.ckpt") + " -o " + dir.file("t.exr"));
  EXPECT_EQ(timed.exitCode, 2) << timed.output;
  EXPECT_FALSE(fs::exists(dir.file("t.exr")));
}

// --display: the image goes to tev as it converges; the test server checks every packet
// against the protocol and assembles the image, whose last state is the final image, bit for
// bit. A display that is not there is a warning; the render goes on.
TEST(LongRenderCli, DisplayStreamsTheImageToTev) {
  test::TempDir dir;
  const std::string out = dir.file("shown.exr");
  std::string command;
  {
    test::TevTestServer server;
    command = "render -q " + defaultScene() + " --width 640 --height 480 --spp " + std::to_string(std::max(1, 4 / kSlowdown)) +
              " --display 127.0.0.1:" +
              std::to_string(server.port()) + " -o " + out;
    test::CommandResult r = test::runCli(command);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(server.waitForClose(60));
    EXPECT_TRUE(server.errors.empty()) << server.errors.front();
    EXPECT_EQ(server.creates, 1);
    EXPECT_GE(server.updates, 4);  // 3.7 MB: strips of about 1 MB
    EXPECT_LE(server.largestPacket, size_t(1.1e6));
    EXPECT_EQ(server.name, "shown.exr");
    EXPECT_EQ(server.channels, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_EQ(server.image.width, 640);
    EXPECT_EQ(server.image.height, 480);
    EXPECT_TRUE(sameBits(server.image, readImage(out)));
  }
  // Nobody listening (the server above has closed): a warning, then the render.
  test::CommandResult alone = test::runCli(command);
  EXPECT_EQ(alone.exitCode, 0) << alone.output;
  EXPECT_NE(alone.output.find("cannot connect to the display"), std::string::npos) << alone.output;
}

}  // namespace
}  // namespace erpt
