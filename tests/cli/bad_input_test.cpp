// Every class of bad input gives a one-line error naming file:line and the cause, a
// non-zero exit code, and no output image (not even a partial one).
#include <gtest/gtest.h>

#include <utility>

#include <filesystem>

#include "support/test_support.h"

namespace erpt {
namespace {

using test::TempDir;

struct BadCase {
  const char* name;
  const char* sceneXml;     // written to scene.xml
  const char* extraFile;    // "name=contents" written beside it, or nullptr
  const char* extraArgs;    // appended to the command line
  int line;                 // expected line in scene.xml; 0: the message names another file
  const char* fileInMessage;  // file expected in the message when line == 0
  const char* cause;        // expected substring of the message
};

const BadCase kCases[] = {
    {"MalformedXml", "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n</scene>\n", nullptr, "", 3, nullptr,
     "malformed XML"},
    {"MissingMeshFile",
     "<scene version=\"3.0.0\">\n  <shape type=\"obj\">\n    <string name=\"filename\" value=\"nope.obj\"/>\n  "
     "</shape>\n</scene>\n",
     nullptr, "", 3, nullptr, "not found"},
    {"MissingTextureFile",
     "<scene version=\"3.0.0\">\n<shape type=\"cube\"><bsdf type=\"diffuse\">\n<texture type=\"bitmap\" "
     "name=\"reflectance\">\n<string name=\"filename\" value=\"missing.png\"/>\n</texture></bsdf></shape>\n</scene>\n",
     nullptr, "", 4, nullptr, "not found"},
    {"SkyTurbidityOutOfRange",
     "<scene version=\"0.6.0\">\n  <shape type=\"cube\"/>\n  <emitter type=\"sky\">\n"
     "    <float name=\"turbidity\" value=\"11\"/>\n  </emitter>\n</scene>\n",
     nullptr, "", 3, nullptr, "turbidity must be in [1, 10]"},
    {"SkySunBelowTheHorizon",
     "<scene version=\"0.6.0\">\n  <shape type=\"cube\"/>\n  <emitter type=\"sky\">\n"
     "    <vector name=\"sunDirection\" x=\"0\" y=\"-1\" z=\"0.2\"/>\n  </emitter>\n</scene>\n",
     nullptr, "", 3, nullptr, "below the horizon"},
    {"SkySunDirectionAndTimeTogether",
     "<scene version=\"0.6.0\">\n  <shape type=\"cube\"/>\n  <emitter type=\"sky\">\n"
     "    <vector name=\"sunDirection\" x=\"0\" y=\"1\" z=\"0\"/>\n    <float name=\"hour\" value=\"9\"/>\n"
     "  </emitter>\n</scene>\n",
     nullptr, "", 3, nullptr, "not both"},
    {"SunskyAbsurdResolution",
     "<scene version=\"0.6.0\">\n  <shape type=\"cube\"/>\n  <emitter type=\"sunsky\">\n"
     "    <integer name=\"resolution\" value=\"1000000\"/>\n  </emitter>\n</scene>\n",
     nullptr, "", 3, nullptr, "resolution must be in [2, 8192]"},
    {"SunNegativeRadiusScale",
     "<scene version=\"0.6.0\">\n  <shape type=\"cube\"/>\n  <emitter type=\"sun\">\n"
     "    <float name=\"sunRadiusScale\" value=\"-1\"/>\n  </emitter>\n</scene>\n",
     nullptr, "", 3, nullptr, "sun_radius_scale must be in [0, 100]"},
    {"MissingEnvironmentMap",
     "<scene version=\"3.0.0\">\n  <shape type=\"cube\"/>\n  <emitter type=\"envmap\">\n"
     "    <string name=\"filename\" value=\"sky.exr\"/>\n  </emitter>\n</scene>\n",
     nullptr, "", 4, nullptr, "not found"},
    {"CorruptEnvironmentMap",
     "<scene version=\"3.0.0\">\n  <shape type=\"cube\"/>\n  <emitter type=\"envmap\">\n"
     "    <string name=\"filename\" value=\"sky.hdr\"/>\n  </emitter>\n</scene>\n",
     "sky.hdr=not an image", "", 4, nullptr, "sky.hdr: cannot read image"},
    {"BlendWithOnePart",
     "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <bsdf type=\"blendbsdf\">\n"
     "      <bsdf type=\"diffuse\"/>\n    </bsdf>\n  </shape>\n</scene>\n",
     nullptr, "", 3, nullptr, "blendbsdf needs two nested BSDFs"},
    {"NormalMapWithoutTexture",
     "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <bsdf type=\"normalmap\">\n"
     "      <bsdf type=\"diffuse\"/>\n    </bsdf>\n  </shape>\n</scene>\n",
     nullptr, "", 3, nullptr, "normalmap needs a <texture>"},
    {"BumpMapWithoutBsdf",
     "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <bsdf type=\"bumpmap\">\n"
     "      <texture type=\"checkerboard\"/>\n    </bsdf>\n  </shape>\n</scene>\n",
     nullptr, "", 3, nullptr, "bumpmap needs a nested <bsdf>"},
    {"BumpMapHeightsMissing",
     "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <bsdf type=\"bumpmap\">\n"
     "      <texture type=\"bitmap\">\n        <string name=\"filename\" value=\"h.exr\"/>\n      </texture>\n"
     "      <bsdf type=\"diffuse\"/>\n    </bsdf>\n  </shape>\n</scene>\n",
     nullptr, "", 5, nullptr, "not found"},
    {"BadNumber",
     "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\">\n    <float name=\"fov\" value=\"4o\"/>\n  "
     "</sensor>\n  <shape type=\"cube\"/>\n</scene>\n",
     nullptr, "", 3, nullptr, "bad number '4o'"},
    {"NonFiniteValue",
     "<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n    <float name=\"radius\" value=\"inf\"/>\n  "
     "</shape>\n</scene>\n",
     nullptr, "", 3, nullptr, "non-finite value"},
    {"NanInTransform",
     "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <transform name=\"to_world\">\n      <translate "
     "x=\"nan\"/>\n    </transform>\n  </shape>\n</scene>\n",
     nullptr, "", 4, nullptr, "non-finite value"},
    {"NegativeSphereRadius",
     "<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n    <float name=\"radius\" value=\"-1\"/>\n  "
     "</shape>\n</scene>\n",
     nullptr, "", 3, nullptr, "sphere radius must be positive"},
    {"SphereCentreOverflowsAfterTransform",
     "<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n    <point name=\"center\" value=\"1e30, 0, 0\"/>\n"
     "    <transform name=\"to_world\"><scale value=\"1e30\"/></transform>\n  </shape>\n</scene>\n",
     nullptr, "", 2, nullptr, "non-finite sphere centre"},
    {"UndefinedParameter",
     "<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n    <float name=\"radius\" value=\"$r\"/>\n  "
     "</shape>\n</scene>\n",
     nullptr, "", 3, nullptr, "undefined parameter '$r'"},
    {"UnknownReference", "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <ref id=\"nothing\"/>\n  </shape>\n</scene>\n",
     nullptr, "", 3, nullptr, "unknown BSDF id 'nothing'"},
    {"UnknownTransformOperation",
     "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <transform name=\"to_world\">\n      <shear "
     "x=\"1\"/>\n    </transform>\n  </shape>\n</scene>\n",
     nullptr, "", 4, nullptr, "unknown transform operation"},
    {"AbsurdFilmSize",
     "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\">\n    <film type=\"hdrfilm\">\n      <integer "
     "name=\"width\" value=\"-5\"/>\n    </film>\n  </sensor>\n  <shape type=\"cube\"/>\n</scene>\n",
     nullptr, "", 3, nullptr, "film size"},
    {"IncludeCycle", "<scene version=\"3.0.0\">\n  <include filename=\"scene.xml\"/>\n</scene>\n", nullptr, "", 2, nullptr,
     "include cycle"},
    {"WrongRoot", "<?xml version=\"1.0\"?>\n<scenery version=\"3.0.0\"/>\n", nullptr, "", 2, nullptr, "expected <scene>"},
    {"MalformedPly",
     "<scene version=\"3.0.0\">\n  <shape type=\"ply\">\n    <string name=\"filename\" value=\"m.ply\"/>\n  "
     "</shape>\n</scene>\n",
     "m.ply=ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
     "z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n",
     "", 0, "m.ply:11", "bad number"},
    {"NonFiniteObjVertex",
     "<scene version=\"3.0.0\">\n  <shape type=\"obj\">\n    <string name=\"filename\" value=\"m.obj\"/>\n  "
     "</shape>\n</scene>\n",
     "m.obj=v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n", "", 0, "m.obj:3", "non-finite vertex position"},
    // Found by tests/fuzz: indices past the normals (or uvs) read out of bounds.
    {"ObjNormalIndexOutOfRange",
     "<scene version=\"3.0.0\">\n  <shape type=\"obj\">\n    <string name=\"filename\" value=\"m.obj\"/>\n  "
     "</shape>\n</scene>\n",
     "m.obj=v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//7\n", "", 0, "m.obj:5", "face refers to normal 7"},
    {"ObjUvIndexOutOfRange",
     "<scene version=\"3.0.0\">\n  <shape type=\"obj\">\n    <string name=\"filename\" value=\"m.obj\"/>\n  "
     "</shape>\n</scene>\n",
     "m.obj=v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "", 0, "m.obj:5", "face refers to texture coordinate 2"},
    {"BadDefineOnCommandLine", "<scene version=\"3.0.0\">\n  <shape type=\"cube\"/>\n</scene>\n", nullptr, "-D novalue",
     -1, nullptr, "-D expects name=value"},
};

// Readable test names in ctest output instead of a byte dump.
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, ClearErrorNonZeroExitNoOutput) {
  const BadCase& c = GetParam();
  TempDir dir;
  std::string scene = dir.write("scene.xml", c.sceneXml);
  if (c.extraFile) {
    std::string spec = c.extraFile;
    size_t eq = spec.find('=');
    dir.write(spec.substr(0, eq), spec.substr(eq + 1));
  }
  std::string out = dir.file("out.exr");
  test::CommandResult r = test::runCli("render -q " + scene + " -o " + out + " --spp 1 " + c.extraArgs);
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find(c.cause), std::string::npos) << r.output;
  if (c.line > 0) {
    EXPECT_NE(r.output.find(scene + ":" + std::to_string(c.line) + ": error:"), std::string::npos) << r.output;
  } else if (c.line == 0) {
    EXPECT_NE(r.output.find(c.fileInMessage), std::string::npos) << r.output;
  }
  // The error is one line.
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    std::string name = entry.path().filename().string();
    EXPECT_TRUE(name.find(".exr") == std::string::npos && name.find(".png") == std::string::npos)
        << "unexpected output file " << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Cli, BadInput, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<BadCase>& info) { return std::string(info.param.name); });

TEST(BadInputCli, MissingSceneFile) {
  TempDir dir;
  test::CommandResult r = test::runCli("render -q " + dir.file("none.xml") + " -o " + dir.file("o.exr"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find(dir.file("none.xml") + ": error: cannot open scene file"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("o.exr")));
}

TEST(BadInputCli, AbsurdOptionsAreRejected) {
  TempDir dir;
  std::string scene = dir.write("s.xml", "<scene version=\"3.0.0\"><shape type=\"cube\"/></scene>");
  for (const char* args : {"--spp 0", "--spp -3", "--width 0", "--threads -1", "--max-depth -7", "--max-depth 0",
                           "--filter lanczos", "--integrator bogus"}) {
    test::CommandResult r = test::runCli("render -q " + scene + " -o " + dir.file("o.exr") + " " + args);
    EXPECT_NE(r.exitCode, 0) << args << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("o.exr"))) << args;
  }
  test::CommandResult r = test::runCli("render -q " + scene + " -o " + dir.file("o.png"));
  EXPECT_NE(r.exitCode, 0);
  r = test::runCli("render -q " + scene + " -o " + dir.file("no/such/dir/o.exr"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("does not exist"), std::string::npos) << r.output;
}

// PMC-ER's options: one-line errors naming the option, non-zero exit, no image.
TEST(BadInputCli, AbsurdPmcOptionsAreRejected) {
  TempDir dir;
  std::string scene = dir.write("s.xml", "<scene version=\"3.0.0\"><shape type=\"cube\"/></scene>");
  const std::pair<const char*, const char*> cases[] = {
      {"--population 0", "--population"},
      {"--radii 5,abc", "--radii"},
      {"--radii 5,,10", "--radii"},
      {"--radii 5,-1", "--radii"},
      {"--radii 1,2,3,4,5,6,7,8,9", "--radii"},
      {"--resample-rate 0", "--resample-rate"},
      {"--alpha-floor 0.4", "--alpha-floor"},
      {"--pmc-flow sideways", "--pmc-flow"},
      {"--pmc-adapt always", "--pmc-adapt"},
      {"--mutations-per-member 0", "--mutations-per-member"},
      {"--pmc-flow balance --max-consecutive 10", "--max-consecutive"},
  };
  for (const auto& [args, option] : cases) {
    test::CommandResult r = test::runCli("render -q " + scene + " -o " + dir.file("o.exr") + " --integrator pmc-er " + args);
    EXPECT_NE(r.exitCode, 0) << args << ": " << r.output;
    EXPECT_NE(r.output.find(option), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("o.exr"))) << args;
  }
}

TEST(BadInputCli, UnsupportedPluginIsAWarningNotAnError) {
  TempDir dir;
  std::string scene = dir.write("s.xml",
                                "<scene version=\"3.0.0\">\n<shape type=\"cube\"/>\n<emitter type=\"collimated\"/>\n"
                                "<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/>"
                                "<integer name=\"height\" value=\"8\"/></film></sensor>\n</scene>\n");
  test::CommandResult r = test::runCli("render -q " + scene + " -o " + dir.file("o.exr") + " --spp 1");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find(scene + ":3: warning: emitter 'collimated' is not supported"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("o.exr")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("o.png")));
}

}  // namespace
}  // namespace erpt
