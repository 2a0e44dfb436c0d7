// Every transform is checked where it is read: a transform that would put non-finite numbers
// into single-precision geometry or camera rays is a one-line file:line error naming the
// element, never a crash later (issue: a camera matrix with 1e39 aborted Embree on AVX-512).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "erpt/error.h"
#include "erpt/scene_loader.h"
#include "support/test_support.h"

namespace erpt {
namespace {

struct TransformCase {
  const char* name;
  const char* transform;  // the body of <transform name="to_world">
  const char* cause;      // expected substring of the message
};

// The transform is put on the camera and on a shape; both must be refused.
const TransformCase kBadTransforms[] = {
    {"EntryOverflowsFloat", R"(<matrix value="-1 0 0 0 0 1 0 1 0 0 1e39 6.8 0 0 0 1"/>)", "single-precision"},
    {"TinyHomogeneousW", R"(<matrix value="-1 0 0 0 0 1 0 1 0 0 -1 6.8 0 0 0 1e-45"/>)", "single-precision"},
    {"ZeroHomogeneousW", R"(<matrix value="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 0"/>)", "projective"},
    {"ProjectiveBottomRow", R"(<matrix value="1 0 0 0 0 1 0 0 0 0 1 0 0 0.5 0 1"/>)", "projective"},
    {"ScaleOverflowsFloat", R"(<scale x="1e39"/>)", "single-precision"},
    {"ProductOverflowsFloat", R"(<scale value="1e20"/><scale value="1e20"/>)", "up to this <scale>"},
    {"TranslateOverflowsFloat", R"(<translate x="1e38"/><translate x="1e38"/><translate x="1e38"/><translate x="1e38"/>)",
     "up to this <translate>"},
    // (In a <matrix>: a scale attribute goes through float, where 1e-39 is a denormal that
    // flush-to-zero modes make 0, a legitimate zero scale.)
    {"NearlySingular", R"(<matrix value="1e-39 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/>)", "nearly singular"},
    {"NanInMatrix", R"(<matrix value="1 0 0 0 0 1 0 0 0 0 nan 0 0 0 0 1"/>)", "non-finite"},
};

void PrintTo(const TransformCase& c, std::ostream* os) { *os << c.name; }

class BadTransform : public ::testing::TestWithParam<TransformCase> {};

std::string expectOneLineError(const std::string& path) {
  try {
    loadScene(path);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "scene loaded without an error";
  return "";
}

TEST_P(BadTransform, IsAOneLineErrorAtTheElement) {
  const TransformCase& c = GetParam();
  test::TempDir dir;
  // Line 3 holds the transform's operations (on one line).
  for (const char* owner : {"sensor type=\"perspective\"", "shape type=\"cube\""}) {
    const std::string tag = std::string(owner).substr(0, std::string(owner).find(' '));
    std::ostringstream xml;
    xml << "<scene version=\"3.0.0\">\n  <" << owner << ">\n    <transform name=\"to_world\">" << c.transform
        << "</transform>\n  </" << tag << ">\n  <shape type=\"sphere\"/>\n</scene>\n";
    const std::string path = dir.write("scene.xml", xml.str());
    const std::string message = expectOneLineError(path);
    EXPECT_NE(message.find(path + ":3: error: "), std::string::npos) << owner << ": " << message;
    EXPECT_NE(message.find(c.cause), std::string::npos) << owner << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(Scene, BadTransform, ::testing::ValuesIn(kBadTransforms),
                         [](const auto& info) { return std::string(info.param.name); });

// Transforms that are fine stay fine: a homogeneous scale of the whole matrix is divided out,
// and a zero scale (Mitsuba's way to hide a shape) is not an error.
TEST(TransformChecks, AcceptsHomogeneousScaleAndZeroScale) {
  test::TempDir dir;
  const std::string path = dir.write("scene.xml", R"(<scene version="3.0.0">
  <sensor type="perspective"><transform name="to_world"><matrix value="2 0 0 0 0 2 0 0 0 0 2 -10 0 0 0 2"/></transform></sensor>
  <shape type="cube"><transform name="to_world"><scale value="0"/></transform></shape>
  <shape type="sphere"><transform name="to_world"><scale value="1e-30"/><translate x="1e30"/></transform></shape>
  <shape type="sphere"/>
</scene>
)");
  Scene scene = loadScene(path);
  EXPECT_NEAR(scene.camera.toWorld(2, 3), -5.0, 1e-12);
  EXPECT_EQ(scene.camera.toWorld(3, 3), 1.0);
}

// The shapes of an instance are placed by the product of the instance's transform and the
// group's members' own: the product is checked too.
TEST(TransformChecks, InstanceProductIsChecked) {
  test::TempDir dir;
  const std::string path = dir.write("scene.xml", R"(<scene version="3.0.0">
  <shape type="shapegroup" id="g">
    <shape type="cube"><transform name="to_world"><scale value="1e15"/></transform></shape>
  </shape>
  <shape type="instance"><ref id="g"/><transform name="to_world"><scale value="1e25"/></transform></shape>
  <shape type="sphere"/>
</scene>
)");
  const std::string message = expectOneLineError(path);
  EXPECT_NE(message.find("single-precision"), std::string::npos) << message;
  EXPECT_TRUE(std::regex_search(message, std::regex(":[0-9]+: error: "))) << message;
}

// The issue's reproduction: the shared Cornell box with an overflowing camera matrix. Before
// the checks this aborted inside Embree on AVX-512 machines (rc 134) and rendered garbage
// elsewhere; now it is a clear error on every machine, with no output written.
TEST(TransformChecks, CornellBoxCameraOverflowIsAnErrorNotACrash) {
  std::ifstream in(test::sharedScenesDir() + "/cornell-box/scene.xml");
  ASSERT_TRUE(in) << "shared Cornell box missing";
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  const std::string camera = "-1 0 0 0 0 1 0 1 0 0 -1 6.8 0 0 0 1";
  const size_t at = xml.find(camera);
  ASSERT_NE(at, std::string::npos);
  const int line = 1 + int(std::count(xml.begin(), xml.begin() + long(at), '\n'));
  for (const char* bad : {"-1 0 0 0 0 1 0 1 0 0 1e39 6.8 0 0 0 1", "-1 0 0 0 0 1 0 1 0 0 -1 6.8 0 0 0 1e-45"}) {
    test::TempDir dir;
    std::string mutated = xml;
    mutated.replace(at, camera.size(), bad);
    const std::string path = dir.write("scene.xml", mutated);
    test::CommandResult r = test::runCli("render -q " + path + " -o " + dir.file("out.exr") + " --spp 1 --width 16 --height 16");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find(path + ":" + std::to_string(line) + ": error: <matrix>"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.exr")));
  }
}

}  // namespace
}  // namespace erpt
