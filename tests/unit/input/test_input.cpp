// Unit tests of the input module, with the app's whole schema: defaults, one-paragraph errors
// (file, path, allowed), overrides, pass-through sublists, cross checks and the generated
// documentation.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "emcontact/app/input_schema.hpp"
#include "emcontact/contact/pairs.hpp"
#include "emcontact/error.hpp"
#include "emcontact/input/detail.hpp"
#include "emcontact/input/echo.hpp"
#include "emcontact/input/input.hpp"
#include "emcontact/time/parameters.hpp"
#include "kernels/em_tet4.hpp"

namespace {

namespace fs = std::filesystem;
using emc::app::read_input;
using Teuchos::Array;
using Teuchos::ParameterList;

/// Parts of a small valid input (one box body "ball"); each test adds or replaces pieces.
struct Xml {
  std::string time = R"(<Parameter name="dt" type="double" value="0.01"/>
      <Parameter name="end" type="double" value="0.02"/>)";
  std::string material = R"(<Parameter name="young" type="double" value="1e5"/>)";
  std::string initial;
  std::string mesh = R"X(<Parameter name="type" type="string" value="box"/>
        <Parameter name="upper corner" type="Array(double)" value="{0.1, 0.1, 0.1}"/>
        <Parameter name="size" type="double" value="0.05"/>)X";
  std::string bodies_extra;
  std::string sections;  ///< more top-level sublists

  std::string str() const {
    return R"(<ParameterList name="test">
  <ParameterList name="Time">
      )" + time +
           R"(
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="ball">
      <ParameterList name="Mesh">
        )" +
           mesh + R"(
      </ParameterList>
      <ParameterList name="Material">
        )" +
           material + R"(
      </ParameterList>
      <ParameterList name="Initial">
        )" +
           initial + R"(
      </ParameterList>
    </ParameterList>
    )" + bodies_extra +
           R"(
  </ParameterList>
  )" + sections +
           R"(
</ParameterList>
)";
  }
};

class InputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("emc_test_input_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& text, const std::string& name = "in.xml") {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  emc::input::Input read(const Xml& xml, const std::vector<std::string>& overrides = {}) {
    return read_input(write(xml.str()), overrides);
  }
  /// The InputError message of reading `xml` (with `overrides`), "" if none was thrown.
  std::string error(const Xml& xml, const std::vector<std::string>& overrides = {}) {
    return error_of_file(write(xml.str()), overrides);
  }
  std::string error_of_file(const std::string& file, const std::vector<std::string>& overrides) {
    try {
      read_input(file, overrides);
    } catch (const emc::InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

/// Checks `message` is one line and contains every one of `parts`.
void expect_message(const std::string& message, const std::vector<std::string>& parts) {
  ASSERT_FALSE(message.empty()) << "no InputError";
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  for (const auto& p : parts)
    EXPECT_NE(message.find(p), std::string::npos) << p << " | " << message;
}

Array<double> vec(double x, double y, double z) {
  return Teuchos::tuple(x, y, z);
}

// ---------------------------------------------------------------- defaults

TEST_F(InputTest, DefaultsAreFilled) {
  const auto in = read(Xml{});
  const ParameterList& p = *in.params;
  EXPECT_EQ(in.dir, dir_.string());
  const auto& time = p.sublist("Time");
  EXPECT_EQ(time.get<double>("dt"), 0.01);
  EXPECT_EQ(time.get<std::string>("integrator"), "energy-momentum");
  EXPECT_EQ(time.get<int>("max step cuts"), 6);
  EXPECT_EQ(time.get<int>("grow after"), 4);
  const auto& body = p.sublist("Bodies").sublist("ball");
  EXPECT_EQ(body.sublist("Material").get<double>("young"), 1e5);
  EXPECT_EQ(body.sublist("Material").get<double>("poisson"), 0.3);
  EXPECT_EQ(body.sublist("Material").get<double>("density"), 1000.0);
  EXPECT_EQ(body.sublist("Initial").get<Array<double>>("velocity"), vec(0, 0, 0));
  EXPECT_EQ(body.sublist("Initial").get<Array<double>>("angular velocity"), vec(0, 0, 0));
  EXPECT_TRUE(body.sublist("Mesh").isParameter("lower corner"));  // mesh defaults too
  EXPECT_EQ(p.sublist("Loads").get<Array<double>>("gravity"), vec(0, 0, 0));
  EXPECT_TRUE(p.isSublist("Dirichlet"));
  EXPECT_EQ(p.sublist("Dirichlet").numParams(), 0);
  EXPECT_TRUE(p.isSublist("Contact"));
  EXPECT_EQ(p.sublist("Contact").numParams(), 0);
  EXPECT_EQ(body.sublist("Mesh").get<double>("half width"), 1.0);
  const auto& newton = p.sublist("Solver").sublist("Newton");
  EXPECT_EQ(newton.get<double>("relative tolerance"), 1e-10);
  EXPECT_EQ(newton.get<double>("absolute tolerance"), 0.0);
  EXPECT_EQ(newton.get<int>("max iterations"), 25);
  const auto& linear = p.sublist("Solver").sublist("Linear");
  EXPECT_EQ(linear.get<std::string>("type"), "gmres");
  EXPECT_EQ(linear.get<std::string>("preconditioner"), "auto");
  EXPECT_EQ(linear.get<double>("tolerance"), 1e-10);
  EXPECT_EQ(linear.get<int>("max iterations"), 1000);
  EXPECT_EQ(linear.get<bool>("reuse preconditioner"), true);
  EXPECT_EQ(linear.get<double>("residual check factor"), 100.0);
  EXPECT_EQ(p.sublist("Solver").sublist("Assembly").get<std::string>("scatter"), "auto");
  EXPECT_TRUE(linear.isSublist("Belos") && linear.isSublist("Ifpack2") &&
              linear.isSublist("MueLu"));
  const auto& output = p.sublist("Output");
  EXPECT_EQ(output.get<std::string>("directory"), "output");
  EXPECT_EQ(output.get<int>("every"), 10);
  EXPECT_EQ(output.get<bool>("progress"), true);
}

TEST_F(InputTest, IntegralValueOfChoices) {
  Xml x;
  x.time += R"(<Parameter name="integrator" type="string" value="midpoint"/>)";
  const auto in = read(x);
  EXPECT_EQ(
      Teuchos::getIntegralValue<emc::kernels::Integrator>(in.params->sublist("Time"), "integrator"),
      emc::kernels::Integrator::midpoint);
  // the time module's settings read it once, with the rest of `Time` and `Solver/Newton`
  const auto& P = *in.params;
  const auto ts =
      emc::time::read_settings(P.sublist("Time"), P.sublist("Solver").sublist("Newton"));
  EXPECT_EQ(ts.integrator, emc::kernels::Integrator::midpoint);
  EXPECT_EQ(ts.step.dt, P.sublist("Time").get<double>("dt"));
  EXPECT_EQ(ts.settle.max_steps, 0);
  EXPECT_EQ(ts.newton.max_iterations, 25);
}

// ---------------------------------------------------------------- bad values

TEST_F(InputTest, NegativeDtRefused) {
  Xml x;
  x.time = R"(<Parameter name="dt" type="double" value="-0.01"/>)";
  expect_message(error(x), {"in.xml: parameter \"Time/dt\"", "-0.01", "allowed: a double > 0"});
}

TEST_F(InputTest, PoissonOneHalfRefused) {
  Xml x;
  x.material += R"(<Parameter name="poisson" type="double" value="0.5"/>)";
  expect_message(error(x),
                 {"in.xml: parameter \"Bodies/ball/Material/poisson\"", ">= 0 and <= 0.49999"});
}

TEST_F(InputTest, UnknownIntegratorRefused) {
  Xml x;
  x.time += R"(<Parameter name="integrator" type="string" value="leapfrog"/>)";
  expect_message(error(x), {"parameter \"Time/integrator\"", "\"leapfrog\"",
                            "allowed: one of \"energy-momentum\", \"midpoint\""});
}

TEST_F(InputTest, UnknownScatterRefused) {
  expect_message(error(Xml{}, {"Solver/Assembly/scatter=colored"}),
                 {"\"Solver/Assembly/scatter", "\"colored\"",
                  "allowed: one of \"auto\", \"coloured\", \"atomic\""});
}

TEST_F(InputTest, MisspeltNameRefused) {
  Xml x;
  x.material = R"(<Parameter name="youngs" type="double" value="1e5"/>)";
  expect_message(error(x),
                 {"parameter \"Bodies/ball/Material/youngs\"", "unknown name",
                  "did you mean \"young\"", "allowed: model, c2, young, poisson, density"});
}

TEST_F(InputTest, WrongTypeRefused) {
  Xml x;
  x.time = R"(<Parameter name="dt" type="string" value="abc"/>)";
  expect_message(error(x), {"parameter \"Time/dt\"", "has type string", "expected type double",
                            "allowed: a double > 0"});
}

TEST_F(InputTest, IntThatIsNotAnIntRefused) {  // Teuchos would silently read 0
  Xml x;
  x.time += R"(<Parameter name="max step cuts" type="int" value="abc"/>)";
  expect_message(error(x), {"parameter \"Time/max step cuts\"", "\"abc\"", "integer"});
}

TEST_F(InputTest, IntOutOfRangeRefused) {
  Xml x;
  x.time += R"(<Parameter name="max step cuts" type="int" value="21"/>)";
  expect_message(error(x), {"parameter \"Time/max step cuts\"", "from 0 to 20"});
}

TEST_F(InputTest, ArrayOfTwoRefused) {
  Xml x;
  x.initial = R"X(<Parameter name="velocity" type="Array(double)" value="{1, 2}"/>)X";
  expect_message(error(x),
                 {"parameter \"Bodies/ball/Initial/velocity\"", "has 2 components", "3 numbers"});
}

TEST_F(InputTest, MeshArrayOfTwoRefused) {
  Xml x;
  x.mesh += R"X(<Parameter name="lower corner" type="Array(double)" value="{1, 2}"/>)X";
  expect_message(error(x), {"parameter \"Bodies/ball/Mesh/lower corner\"", "3 numbers"});
}

TEST_F(InputTest, UnknownSectionRefused) {
  Xml x;
  x.sections = R"(<ParameterList name="Contacts"/>)";
  expect_message(error(x), {"parameter \"Contacts\"", "unknown section", "did you mean \"Contact\"",
                            "Time, Bodies, Loads, Dirichlet, Contact, Solver, Output"});
}

TEST_F(InputTest, SublistGivenAsParameterRefused) {
  Xml x;
  x.sections = R"(<Parameter name="Output" type="int" value="1"/>)";
  expect_message(error(x), {"parameter \"Output\"", "must be a sublist"});
}

TEST_F(InputTest, DuplicateNameRefused) {
  Xml x;
  x.time += R"(<Parameter name="dt" type="double" value="0.02"/>)";
  expect_message(error(x), {"parameter \"Time/dt\"", "given twice"});
}

TEST_F(InputTest, MissingFileRefused) {
  const std::string file = (dir_ / "missing.xml").string();
  expect_message(error_of_file(file, {}), {file + ": cannot read", "no such file"});
}

TEST_F(InputTest, MalformedXmlRefused) {
  const std::string file = write("<ParameterList name=\"x\">\n  <ParameterList name=\"Time\">\n");
  expect_message(error_of_file(file, {}), {file + ": cannot read", "XML parse error"});
}

// ---------------------------------------------------------------- cross checks

TEST_F(InputTest, NoBodyRefused) {
  const std::string file = write(R"(<ParameterList name="x"><ParameterList name="Bodies"/>
    </ParameterList>)");
  expect_message(error_of_file(file, {}), {"parameter \"Bodies\"", "no body", "at least one"});
}

TEST_F(InputTest, EndBeforeDtRefused) {
  Xml x;
  x.time = R"(<Parameter name="dt" type="double" value="0.1"/>
              <Parameter name="end" type="double" value="0.05"/>)";
  expect_message(error(x), {"parameter \"Time/end\"", "smaller than dt"});
}

TEST_F(InputTest, DirichletOnUnknownBodyRefused) {
  Xml x;
  x.sections = R"(<ParameterList name="Dirichlet"><ParameterList name="fix">
      <Parameter name="body" type="string" value="bal"/>
      <Parameter name="surface" type="string" value="zmin"/>
    </ParameterList></ParameterList>)";
  expect_message(error(x), {"parameter \"Dirichlet/fix/body\"", "\"bal\" is not a body",
                            "allowed: the name of a body: ball"});
}

TEST_F(InputTest, DirichletWithoutSurfaceRefused) {
  Xml x;
  x.sections = R"(<ParameterList name="Dirichlet"><ParameterList name="fix">
      <Parameter name="body" type="string" value="ball"/>
    </ParameterList></ParameterList>)";
  expect_message(error(x), {"parameter \"Dirichlet/fix/surface\"", "required"});
}

TEST_F(InputTest, DirichletAccepted) {
  Xml x;
  x.sections = R"(<ParameterList name="Dirichlet"><ParameterList name="fix">
      <Parameter name="body" type="string" value="ball"/>
      <Parameter name="surface" type="string" value="zmin"/>
    </ParameterList></ParameterList>)";
  const auto in = read(x);
  EXPECT_EQ(in.params->sublist("Dirichlet").sublist("fix").get<std::string>("surface"), "zmin");
}

// ---------------------------------------------------------------- contact pairs

/// A rigid plane body "floor" (no Material, no Initial) next to the box "ball".
const char* const kFloor = R"(<ParameterList name="floor">
      <ParameterList name="Mesh">
        <Parameter name="type" type="string" value="plane"/>
        <Parameter name="half width" type="double" value="2"/>
      </ParameterList>
    </ParameterList>)";

/// `x` with the floor and the contact pair "drop" made of `entries`.
Xml with_pair(const std::string& entries, Xml x = Xml{}) {
  x.bodies_extra += kFloor;
  x.sections += R"(<ParameterList name="Contact"><ParameterList name="drop">)" + entries +
                "</ParameterList></ParameterList>";
  return x;
}

std::string param(const std::string& name, const std::string& value,
                  const std::string& type = "string") {
  return "<Parameter name=\"" + name + "\" type=\"" + type + "\" value=\"" + value + "\"/>";
}

const std::string kBallOnFloor = param("slave", "ball") + param("master", "floor");

TEST_F(InputTest, ContactPairDefaults) {
  const auto in = read(with_pair(kBallOnFloor));
  const auto& pair = in.params->sublist("Contact").sublist("drop");
  EXPECT_EQ(pair.get<std::string>("slave"), "ball");
  EXPECT_EQ(pair.get<std::string>("master"), "floor");
  EXPECT_EQ(pair.get<std::string>("type"), "full stick");
  EXPECT_EQ(Teuchos::getIntegralValue<emc::contact::Kind>(pair, "type"),
            emc::contact::Kind::full_stick);
  EXPECT_EQ(pair.get<double>("max penetration"), 0.0);
  // The rigid body keeps the defaults of what it does not need.
  const auto& floor = in.params->sublist("Bodies").sublist("floor");
  EXPECT_EQ(floor.sublist("Mesh").get<std::string>("type"), "plane");
  EXPECT_EQ(floor.sublist("Mesh").get<double>("half width"), 2.0);
  EXPECT_EQ(floor.sublist("Material").get<double>("young"), 1e6);
  EXPECT_EQ(floor.sublist("Initial").get<Array<double>>("velocity"), vec(0, 0, 0));
}

TEST_F(InputTest, ContactPairWithSurfacesAndEveryParameter) {
  Xml x;
  x.bodies_extra = R"(<ParameterList name="plate"><ParameterList name="Mesh">
        <Parameter name="type" type="string" value="box"/>
      </ParameterList></ParameterList>)";
  const auto in =
      read(with_pair(param("slave", "ball/zmin") + param("master", "plate/zmax") +
                         param("type", "frictionless") + param("max penetration", "0.01", "double"),
                     x));
  const auto& pair = in.params->sublist("Contact").sublist("drop");
  EXPECT_EQ(pair.get<std::string>("slave"), "ball/zmin");
  EXPECT_EQ(pair.get<std::string>("master"), "plate/zmax");
  EXPECT_EQ(Teuchos::getIntegralValue<emc::contact::Kind>(pair, "type"),
            emc::contact::Kind::frictionless);
  EXPECT_EQ(pair.get<double>("max penetration"), 0.01);
}

TEST_F(InputTest, ContactOnUnknownBodyRefused) {
  expect_message(error(with_pair(param("slave", "bal") + param("master", "floor"))),
                 {"in.xml: parameter \"Contact/drop/slave\"", "\"bal\" is not a body",
                  "allowed: a body name or body/surface", "bodies: ball, floor"});
  expect_message(error(with_pair(param("slave", "ball") + param("master", "flor/top"))),
                 {"parameter \"Contact/drop/master\"", "\"flor\" (in \"flor/top\") is not a body",
                  "bodies: ball, floor"});
  expect_message(error(with_pair(param("master", "floor"))),
                 {"parameter \"Contact/drop/slave\"", "missing (required)"});
  expect_message(error(with_pair(param("slave", "ball"))),
                 {"parameter \"Contact/drop/master\"", "missing (required)"});
  expect_message(error(with_pair(param("slave", "ball/") + param("master", "floor"))),
                 {"parameter \"Contact/drop/slave\"", "no surface name after \"ball/\""});
}

TEST_F(InputTest, ContactOnOneBodyRefused) {
  expect_message(error(with_pair(param("slave", "ball/zmin") + param("master", "ball/zmax"))),
                 {"in.xml: parameter \"Contact/drop/master\"", "\"ball\" is also the slave's body",
                  "self-contact is not supported", "allowed: a body other than \"ball\": floor"});
}

TEST_F(InputTest, RigidSlaveRefused) {
  expect_message(error(with_pair(param("slave", "floor") + param("master", "ball"))),
                 {"in.xml: parameter \"Contact/drop/slave\"",
                  "body \"floor\" is a rigid surface (Mesh type \"plane\")",
                  "the slave must be a deformable body", "allowed: a deformable body: ball"});
  Xml x;
  x.mesh = R"X(<Parameter name="type" type="string" value="rectangle"/>)X";  // ball rigid too
  expect_message(error(with_pair(param("slave", "ball/surface") + param("master", "floor"), x)),
                 {"parameter \"Contact/drop/slave\"", "(Mesh type \"rectangle\")",
                  "allowed: a deformable body: (none in the input)"});
}

TEST_F(InputTest, BadContactTypeAndPenetrationRefused) {
  expect_message(error(with_pair(kBallOnFloor + param("type", "sticky"))),
                 {"in.xml: parameter \"Contact/drop/type\"", "\"sticky\"",
                  "allowed: one of \"full stick\", \"frictionless\", \"coulomb\""});
  expect_message(error(with_pair(kBallOnFloor + param("max penetration", "-0.001", "double"))),
                 {"in.xml: parameter \"Contact/drop/max penetration\"", "-0.001", "out of range",
                  "allowed: a double >= 0"});
  expect_message(error(with_pair(kBallOnFloor + param("slaves", "ball"))),
                 {"parameter \"Contact/drop/slaves\"", "unknown name", "did you mean \"slave\""});
  Xml x;
  x.sections = R"(<ParameterList name="Contact"><Parameter name="drop" type="int" value="1"/>
    </ParameterList>)";
  expect_message(error(x), {"parameter \"Contact/drop\"", "must be a sublist (one per pair)",
                            "slave, master, type, max penetration"});
}

TEST_F(InputTest, MovingRigidBodyRefused) {
  Xml x;
  x.bodies_extra = R"X(<ParameterList name="floor">
      <ParameterList name="Mesh"><Parameter name="type" type="string" value="plane"/></ParameterList>
      <ParameterList name="Initial">
        <Parameter name="velocity" type="Array(double)" value="{0, 0, -1}"/>
      </ParameterList>
    </ParameterList>)X";
  expect_message(error(x), {"in.xml: parameter \"Bodies/floor/Initial/velocity\"",
                            "value {0, 0, -1} on a rigid surface body (Mesh type \"plane\")",
                            "motion of rigid surfaces is fixed for now", "allowed: {0, 0, 0}"});
  // Also through an override, and for the angular velocity and a rectangle.
  Xml y = with_pair(kBallOnFloor);
  expect_message(error(y, {"Bodies/floor/Initial/angular velocity={0,0,1}"}),
                 {"parameter \"Bodies/floor/Initial/angular velocity\"", "rigid surface"});
  expect_message(
      error(y, {"Bodies/floor/Mesh/type=rectangle", "Bodies/floor/Initial/velocity={1,0,0}"}),
      {"parameter \"Bodies/floor/Initial/velocity\"", "(Mesh type \"rectangle\")"});
  // A deformable body may move, and a rigid one may stay at rest.
  EXPECT_EQ(
      error(y, {"Bodies/ball/Initial/velocity={0,0,-1}", "Bodies/floor/Initial/velocity={0,0,0}"}),
      "");
}

TEST_F(InputTest, OverrideOfContactPair) {
  const auto in = read(with_pair(kBallOnFloor),
                       {"Contact/drop/type=frictionless", "Contact/drop/max penetration=0.002",
                        "Contact/drop/slave=ball/zmin"});
  const auto& pair = in.params->sublist("Contact").sublist("drop");
  EXPECT_EQ(pair.get<std::string>("type"), "frictionless");
  EXPECT_EQ(Teuchos::getIntegralValue<emc::contact::Kind>(pair, "type"),
            emc::contact::Kind::frictionless);
  EXPECT_EQ(pair.get<double>("max penetration"), 0.002);
  EXPECT_EQ(pair.get<std::string>("slave"), "ball/zmin");
  expect_message(error(with_pair(kBallOnFloor), {"Contact/drop/type=slip"}),
                 {"override \"Contact/drop/type=slip\"", "\"full stick\", \"frictionless\""});
  expect_message(error(with_pair(kBallOnFloor), {"Contact/lift/type=frictionless"}),
                 {"override \"Contact/lift/type=frictionless\"", "\"lift\" is not a pair", "drop"});
  expect_message(error(with_pair(kBallOnFloor), {"Contact/drop/max penetration=-1"}),
                 {"override \"Contact/drop/max penetration=-1\"", "out of range"});
  expect_message(error(with_pair(kBallOnFloor), {"Contact/drop/master=ball"}),
                 {"parameter \"Contact/drop/master\"", "self-contact"});
}

// ---------------------------------------------------------------- overrides

TEST_F(InputTest, OverridesOfEveryType) {
  const auto in = read(Xml{}, {"Time/end=0.5", "Time/max step cuts=3", "Time/integrator=midpoint",
                               "Output/progress=false", "Bodies/ball/Initial/velocity={1,0,0}",
                               "Bodies/ball/Material/young=4e6", "Solver/Linear/tolerance=1e-8"});
  const ParameterList& p = *in.params;
  EXPECT_EQ(p.sublist("Time").get<double>("end"), 0.5);
  EXPECT_EQ(p.sublist("Time").get<int>("max step cuts"), 3);
  EXPECT_EQ(p.sublist("Time").get<std::string>("integrator"), "midpoint");
  EXPECT_EQ(p.sublist("Output").get<bool>("progress"), false);
  const auto& body = p.sublist("Bodies").sublist("ball");
  EXPECT_EQ(body.sublist("Initial").get<Array<double>>("velocity"), vec(1, 0, 0));
  EXPECT_EQ(body.sublist("Material").get<double>("young"), 4e6);
  EXPECT_EQ(p.sublist("Solver").sublist("Linear").get<double>("tolerance"), 1e-8);
}

TEST_F(InputTest, OverrideOfMeshParameter) {
  const auto in = read(Xml{}, {"Bodies/ball/Mesh/size=0.02"});
  const auto& mesh = in.params->sublist("Bodies").sublist("ball").sublist("Mesh");
  EXPECT_EQ(mesh.get<double>("size"), 0.02);
  Xml file;
  file.mesh = R"(<Parameter name="type" type="string" value="box"/>)";
  const auto in2 = read(file, {"Bodies/ball/Mesh/type=file", "Bodies/ball/Mesh/file=a.msh"});
  EXPECT_EQ(in2.params->sublist("Bodies").sublist("ball").sublist("Mesh").get<std::string>("type"),
            "file");
  expect_message(error(Xml{}, {"Bodies/ball/Mesh/type=sphere"}),
                 {"override \"Bodies/ball/Mesh/type=sphere\"", "\"box\", \"cylinder\""});
}

// A parameter of another mesh type would be silently ignored (a file given to a box).
TEST_F(InputTest, MeshParameterOfAnotherTypeRefused) {
  expect_message(error(Xml{}, {"Bodies/ball/Mesh/file=ball.msh"}),
                 {"in.xml: parameter \"Bodies/ball/Mesh/file\": given, but type \"box\" does not "
                  "read it (it is a parameter of type \"file\")",
                  "allowed: the parameters of type \"box\": type, size, lower corner, upper "
                  "corner; or a type that reads it"});
  // the box's corners with type file in the file itself; a shell's radii on a cylinder
  Xml file;
  file.mesh = std::string(R"(<Parameter name="type" type="string" value="file"/>)") +
              R"X(<Parameter name="upper corner" type="Array(double)" value="{1, 1, 1}"/>)X";
  expect_message(error(file), {"parameter \"Bodies/ball/Mesh/upper corner\"",
                               "type \"file\" does not read it", "types \"box\", \"rectangle\"",
                               "the parameters of type \"file\": type, file, volume"});
  // --set changing the type leaves the file's parameters of its own type alone, not its own
  EXPECT_EQ(error(Xml{}, {"Bodies/ball/Mesh/type=file", "Bodies/ball/Mesh/file=a.msh"}), "");
  expect_message(error(Xml{}, {"Bodies/ball/Mesh/type=file", "Bodies/ball/Mesh/size=0.02"}),
                 {"parameter \"Bodies/ball/Mesh/size\": given, but type \"file\""});
  Xml cyl;
  cyl.mesh = R"(<Parameter name="type" type="string" value="cylinder"/>
        <Parameter name="inner radius" type="double" value="0.05"/>)";
  expect_message(error(cyl), {"parameter \"Bodies/ball/Mesh/inner radius\"",
                              "types \"hollow cylinder\", \"spherical shell\"",
                              "type, size, center, axis, height, radius"});
  // every parameter a type reads is accepted, also when equal to its default
  Xml shell;
  shell.mesh = R"X(<Parameter name="type" type="string" value="spherical shell"/>
        <Parameter name="center" type="Array(double)" value="{0, 0, 0}"/>
        <Parameter name="inner radius" type="double" value="0.05"/>
        <Parameter name="outer radius" type="double" value="0.1"/>
        <Parameter name="size" type="double" value="0.1"/>)X";
  EXPECT_EQ(error(shell), "");
}

TEST_F(InputTest, BodyGivenAsParameterRefused) {
  Xml x;
  x.bodies_extra = R"(<Parameter name="stone" type="int" value="1"/>)";
  expect_message(error(x), {"parameter \"Bodies/stone\"", "must be a sublist (one per body)"});
}

TEST_F(InputTest, OverrideReplacesWrongTypeInFile) {
  Xml x;
  x.time = R"(<Parameter name="dt" type="string" value="abc"/>)";
  const auto in = read(x, {"Time/dt=0.001"});
  EXPECT_EQ(in.params->sublist("Time").get<double>("dt"), 0.001);
}

TEST_F(InputTest, OverrideOfUnknownPathRefused) {
  expect_message(error(Xml{}, {"Time/dtt=1"}), {"override \"Time/dtt=1\"", "unknown parameter",
                                                "did you mean \"dt\"", "dt, end"});
  expect_message(error(Xml{}, {"Timing/dt=1"}), {"override \"Timing/dt=1\"", "unknown section"});
  expect_message(error(Xml{}, {"Bodies/bal/Material/young=1"}),
                 {"override \"Bodies/bal/Material/young=1\"", "\"bal\" is not a body", "ball"});
  expect_message(error(Xml{}, {"Solver/Nwton/max iterations=1"}),
                 {"no sublist \"Nwton\"", "Newton, Linear"});
  expect_message(error(Xml{}, {"Solver/Newton=1"}), {"\"Newton\" is a sublist"});
  expect_message(error(Xml{}, {"Time/dt"}), {"override \"Time/dt\"", "name=value"});
}

TEST_F(InputTest, OverrideWithBadValueRefused) {
  expect_message(error(Xml{}, {"Time/dt=abc"}),
                 {"override \"Time/dt=abc\"", "not a valid double", "allowed: a double > 0"});
  expect_message(error(Xml{}, {"Time/dt=-1"}),
                 {"override \"Time/dt=-1\"", "out of range", "allowed: a double > 0"});
  expect_message(error(Xml{}, {"Time/integrator=euler"}), {"\"midpoint\""});
  expect_message(error(Xml{}, {"Output/progress=maybe"}), {"bool"});
  expect_message(error(Xml{}, {"Time/grow after=1.5"}), {"not a valid int"});
  expect_message(error(Xml{}, {"Loads/gravity={0,-9.81}"}),
                 {"override \"Loads/gravity={0,-9.81}\"", "has 2 components"});
}

// ---------------------------------------------------------------- pass-through sublists

TEST_F(InputTest, PassThroughAcceptsAnyContent) {
  Xml x;
  x.sections = R"(<ParameterList name="Solver"><ParameterList name="Linear">
      <ParameterList name="Belos">
        <Parameter name="Convergence Tolerance" type="double" value="1e-5"/>
        <Parameter name="Orthogonalization" type="string" value="ICGS"/>
      </ParameterList>
      <ParameterList name="MueLu">
        <Parameter name="verbosity" type="string" value="none"/>
        <ParameterList name="level 0"><Parameter name="x" type="int" value="1"/></ParameterList>
      </ParameterList>
    </ParameterList></ParameterList>)";
  const auto in = read(x, {"Solver/Linear/Belos/Maximum Iterations=50",
                           "Solver/Linear/Belos/Convergence Tolerance=0.5",
                           "Solver/Linear/Belos/Implicit Residual Scaling=Norm of RHS",
                           "Solver/Linear/Ifpack2/fact: drop tolerance=0.5",
                           "Solver/Linear/Ifpack2/schwarz: use reordering=true",
                           "Solver/Linear/MueLu/smoother: params/relaxation: sweeps=2"});
  const auto& linear = in.params->sublist("Solver").sublist("Linear");
  const auto& belos = linear.sublist("Belos");
  EXPECT_EQ(belos.get<int>("Maximum Iterations"), 50);
  EXPECT_EQ(belos.get<double>("Convergence Tolerance"), 0.5);  // keeps the file's type
  EXPECT_EQ(belos.get<std::string>("Orthogonalization"), "ICGS");
  EXPECT_EQ(belos.get<std::string>("Implicit Residual Scaling"), "Norm of RHS");
  EXPECT_EQ(linear.sublist("Ifpack2").get<double>("fact: drop tolerance"), 0.5);
  EXPECT_EQ(linear.sublist("Ifpack2").get<bool>("schwarz: use reordering"), true);
  const auto& muelu = linear.sublist("MueLu");
  EXPECT_EQ(muelu.get<std::string>("verbosity"), "none");
  EXPECT_EQ(muelu.sublist("level 0").get<int>("x"), 1);
  EXPECT_EQ(muelu.sublist("smoother: params").get<int>("relaxation: sweeps"), 2);
}

TEST_F(InputTest, PassThroughOverrideKeepsExistingType) {
  Xml x;
  x.sections = R"(<ParameterList name="Solver"><ParameterList name="Linear">
      <ParameterList name="Belos"><Parameter name="Num Blocks" type="int" value="30"/></ParameterList>
    </ParameterList></ParameterList>)";
  expect_message(error(x, {"Solver/Linear/Belos/Num Blocks=abc"}), {"not a valid int"});
}

// ---------------------------------------------------------------- extreme values

// Values no solid has, or that overflow, are refused naming the parameter (they failed as a
// step that named nothing); real materials in SI and in the tonne-millimetre units are not.
TEST_F(InputTest, ExtremeValuesRefusedNamingTheParameter) {
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"Bodies/ball/Material/density=1e308", "allowed: a double >= 1e-12 and <= 1e6"},
      {"Bodies/ball/Material/young=1e308", "allowed: a double >= 1e-6 and <= 1e14"},
      {"Bodies/ball/Material/young=4.9e-324", "allowed: a double >= 1e-6 and <= 1e14"},
      {"Bodies/ball/Material/poisson=0.4999999999", "allowed: a double >= 0 and <= 0.49999"},
      {"Bodies/ball/Initial/velocity={1e20, 0, 0}", "each >= -3e8 and <= 3e8"},
      {"Loads/gravity={0, 0, -1e300}", "each >= -1e12 and <= 1e12"},
      {"Solver/Linear/tolerance=1e300", "allowed: a double > 0 and < 1"}};
  for (const auto& [set, allowed] : refused)
    expect_message(error(Xml{}, {set}), {"override \"" + set + "\"", "out of range", allowed});
  expect_message(error(Xml{}, {"Solver/Linear/Belos/Maximum Iterations=-1"}),
                 {"parameter \"Solver/Linear/Belos/Maximum Iterations\": value -1 is out of "
                  "range; allowed: an int >= 1"});
  expect_message(error(Xml{}, {"Solver/Linear/Belos/Convergence Tolerance=2"}),
                 {"parameter \"Solver/Linear/Belos/Convergence Tolerance\": value 2"});
  for (const auto& ok : std::vector<std::vector<std::string>>{
           {"Bodies/ball/Material/young=2.1e11", "Bodies/ball/Material/density=7850"},
           {"Bodies/ball/Material/young=1e6", "Bodies/ball/Material/poisson=0.49"},
           {"Bodies/ball/Material/young=2.1e5", "Bodies/ball/Material/density=7.85e-9"},
           {"Bodies/ball/Initial/velocity={1e4, 0, 0}", "Loads/gravity={0, 0, -9.81}"}})
    EXPECT_EQ(error(Xml{}, ok), "") << ok[0];
}

// ---------------------------------------------------------------- encodings

TEST_F(InputTest, Utf8ByteOrderMarkAcceptedUtf16Refused) {
  const std::string text = Xml{}.str();
  EXPECT_EQ(error_of_file(write("\xef\xbb\xbf" + text), {}), "");
  std::string utf16 = "\xff\xfe";
  for (char c : text) utf16 += std::string(1, c) + '\0';
  expect_message(error_of_file(write(utf16, "u16.xml"), {}),
                 {"u16.xml: cannot read the input: it is UTF-16 text (a byte order mark); it must "
                  "be UTF-8 (or ASCII) text"});
  expect_message(error_of_file(write(utf16.substr(2), "le.xml"), {}),
                 {"le.xml: cannot read the input: it holds a NUL byte (byte 1)"});
}

// ---------------------------------------------------------------- helpers and docs

TEST(InputEcho, CutsEscapesAndLists) {
  using emc::input::echo;
  EXPECT_EQ(echo("short"), "short");
  EXPECT_EQ(echo(std::string(80, 'a')), std::string(80, 'a'));
  EXPECT_EQ(echo(std::string(5000, 'a')), std::string(80, 'a') + "... (5000 characters)");
  EXPECT_EQ(echo(std::string("a\0b\n\x01", 5)), "a\\0b\\n\\x01");
  const std::string e = echo(std::string(79, 'x') + "\xc3\xa9\xc3\xa9");  // not inside a character
  EXPECT_EQ(e, std::string(79, 'x') + "\xc3\xa9... (83 characters)");
  EXPECT_EQ(emc::input::echo_list({"a", "b"}), "\"a\", \"b\"");
  EXPECT_EQ(emc::input::echo_list({"a", "b", "c", "d"}, 2), "\"a\", \"b\" and 2 more");
  EXPECT_EQ(emc::input::echo_number(1e300), "1e+300");
}

TEST(InputDetail, FormatsValuesAndRanges) {
  using namespace emc::input::detail;
  EXPECT_EQ(format_double(0.01), "0.01");
  EXPECT_EQ(format_double(1e-10), "1e-10");
  EXPECT_EQ(format_double(1000), "1000");
  EXPECT_EQ(format_double(1e6), "1e6");
  EXPECT_EQ(format_double(-9.81), "-9.81");
  EXPECT_EQ(format_value(Teuchos::any(vec(0, 0, -9.81))), "{0, 0, -9.81}");
  EXPECT_EQ(condense("a.cpp:50:\n\nThrow number = 1\n\nThrow test that evaluated to true: x\n\n"
                     "XML parse error at line 5\n"),
            "XML parse error at line 5");
  EXPECT_EQ(Teuchos::any_cast<int>(guess_value("12")), 12);
  EXPECT_EQ(Teuchos::any_cast<double>(guess_value("1e3")), 1000.0);
  EXPECT_EQ(Teuchos::any_cast<bool>(guess_value("false")), false);
  EXPECT_EQ(Teuchos::any_cast<std::string>(guess_value("ICGS")), "ICGS");
  EXPECT_THROW(parse_value("1.5x", Teuchos::any(1.0)), std::invalid_argument);
  EXPECT_THROW(parse_value("nan", Teuchos::any(1.0)), std::invalid_argument);
}

TEST_F(InputTest, DocumentedExampleIsValid) {
  const auto in = read_input(write(emc::input::detail::example_xml()), {});
  EXPECT_EQ(in.params->sublist("Dirichlet").sublist("clamped end").get<std::string>("body"),
            "block");
}

TEST(InputFiles, CommittedInputsAreValid) {
  const std::string src = EMC_SOURCE_DIR;
  for (const char* f :
       {"/inputs/tumbling_box.xml", "/inputs/falling_box.xml", "/tests/bad_input/good_box.xml"})
    EXPECT_NO_THROW(read_input(src + f, {})) << f;
  const auto tumbling = read_input(src + "/inputs/tumbling_box.xml", {});
  const auto& box = tumbling.params->sublist("Bodies").sublist("box");
  EXPECT_EQ(box.sublist("Initial").get<Array<double>>("angular velocity"), vec(2, 1, 4));
  EXPECT_EQ(tumbling.params->sublist("Time").get<double>("end"), 5.0);
  const auto falling = read_input(src + "/inputs/falling_box.xml", {});
  EXPECT_EQ(falling.params->sublist("Loads").get<Array<double>>("gravity"), vec(0, 0, -9.81));
  EXPECT_EQ(falling.dir, src + "/inputs");
}

TEST(InputFiles, BadInputsAreRefusedByTheInputModule) {
  const std::string dir = std::string(EMC_SOURCE_DIR) + "/tests/bad_input/";
  for (const char* f : {"bad_unknown_parameter.xml", "bad_wrong_type.xml", "bad_negative_dt.xml"})
    EXPECT_THROW(read_input(dir + f, {}), emc::InputError) << f;
  for (const char* f : {"bad_missing_mesh.xml", "bad_inverted_element.xml"})  // mesh errors
    EXPECT_NO_THROW(read_input(dir + f, {})) << f;
}

TEST(InputDocs, TablesListEveryParameter) {
  const std::string md = emc::input::schema_markdown(emc::app::input_schema());
  for (const char* row :
       {"| `dt` | double | `0.01` | > 0 and <= 1e30 |",
        "| `integrator` | string | `energy-momentum` |",
        "| `max step cuts` | int | `6` | from 0 to 20 |",
        "| `poisson` | double | `0.3` | >= 0 and <= 0.49999 |",
        "| `velocity` | Array(double) | `{0, 0, 0}` | 3 numbers, each >= -3e8 and <= 3e8 |",
        "| `Belos` | sublist |", "| `progress` | bool | `true` | `true`, `false` |",
        "### `Bodies/<body>/Mesh`", "### `Dirichlet/<condition>`", "### `Solver/Linear`", "```xml",
        "## Contact", "### `Contact/<pair>`", "| `slave` | string | `\"\"` | any string |",
        "| `type` | string | `full stick` | `full stick`, `frictionless`, `coulomb` |",
        "| `friction coefficient` | double | `0` | >= 0 |",
        "| `max penetration` | double | `0` | >= 0 |", "| `half width` | double | `1` | > 0 |",
        "`spherical shell`, `plane`, `rectangle`, `file`"})
    EXPECT_NE(md.find(row), std::string::npos) << row;
}

TEST(InputSchema, ValidParametersHasEverySection) {
  const auto all = emc::input::valid_parameters(emc::app::input_schema());
  for (const char* s : {"Time", "Bodies", "Loads", "Dirichlet", "Contact", "Solver", "Output"})
    EXPECT_TRUE(all->isSublist(s)) << s;
  EXPECT_TRUE(all->sublist("Contact").sublist("<pair>").isParameter("max penetration"));
  EXPECT_TRUE(all->sublist("Bodies").sublist("<body>").isSublist("Mesh"));
  EXPECT_TRUE(all->sublist("Dirichlet").sublist("<condition>").isParameter("surface"));
}

}  // namespace
