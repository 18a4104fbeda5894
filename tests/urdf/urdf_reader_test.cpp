// Hostile and odd URDF files (issue 29): each is refused with robot.urdf:line:col: error: at the
// place in the file that is wrong and a message that says what was expected, or, where URDF
// allows it, imported into model text that eomgen's own parser reads. Nothing crashes, hangs
// or expands without bound. Places are found in the test's text by a needle, independently of
// the reader's own search.
#include <Eigen/Geometry>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomgen/urdf/urdf_import.hpp"
#include "eomgen/urdf/urdf_robot.hpp"

namespace eomgen {
namespace {

using ::testing::HasSubstr;
using urdf::ImportOptions;
using urdf::ImportResult;

struct Place {
  int line = 0, column = 0;
};

// where `needle` starts in `text` (1-based line and column); the text must hold it once
Place place_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "the test's text lacks '" << needle << "'";
  EXPECT_EQ(text.find(needle, at + 1), std::string::npos) << "the test's text holds '" << needle << "' twice";
  if (at == std::string::npos) return {};
  const std::size_t line_start = text.rfind('\n', at) == std::string::npos ? 0 : text.rfind('\n', at) + 1;
  return {static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n')) + 1,
          static_cast<int>(at - line_start) + 1};
}

ImportResult import_text(const std::string& urdf, const ImportOptions& options = {}) {
  return urdf::write_model(urdf::read_robot(urdf, "robot.urdf"), options);
}

// Reading `urdf` (and writing its model) throws a SourceError at `at` in robot.urdf whose
// message holds each of `words`.
void expect_urdf_error(const std::string& urdf, Place at, const std::vector<std::string>& words,
                       const ImportOptions& options = {}) {
  SCOPED_TRACE("URDF text:\n" + urdf);
  try {
    const ImportResult result = import_text(urdf, options);
    ADD_FAILURE() << "expected a SourceError, got the model\n" << result.text;
  } catch (const SourceError& e) {
    EXPECT_EQ(e.location().file, "robot.urdf");
    EXPECT_EQ(e.location().line, at.line) << e.what();
    EXPECT_EQ(e.location().column, at.column) << e.what();
    for (const std::string& word : words) EXPECT_THAT(e.message(), HasSubstr(word));
    EXPECT_THAT(e.what(), ::testing::StartsWith("robot.urdf:" + std::to_string(at.line) + ":" +
                                                std::to_string(at.column) + ": error: "));
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected a SourceError, got another exception: " << e.what();
  }
}

// The model the import writes, read back by eomgen's own parser (which checks what the model
// language checks: names, inertias, every expression).
Model imported_model(const std::string& urdf, const ImportOptions& options = {}) {
  const ImportResult result = import_text(urdf, options);
  SCOPED_TRACE("model text:\n" + result.text);
  return parse_model(result.text, "robot.urdf (as imported)");
}

std::vector<std::string> coordinate_names(const Model& model) {
  std::vector<std::string> names;
  for (const auto& c : model.system.variables().coordinates()) names.push_back(c.name);
  return names;
}

double output(const NumericEquations& e, const std::string& label) {
  for (const auto& [name, value] : e.outputs)
    if (name == label) return value;
  ADD_FAILURE() << "no output " << label;
  return NAN;
}

double parameter(const Model& model, const std::string& name) {
  for (const auto& p : model.system.variables().parameters())
    if (p.name == name) return p.default_value;
  ADD_FAILURE() << "the model has no parameter " << name;
  return NAN;
}

// a link with a mass and an inertia every body can have
std::string massive_link(const std::string& name) {
  return "  <link name=\"" + name +
         "\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" "
         "izz=\"0.01\"/></inertial></link>\n";
}

std::string revolute(const std::string& name, const std::string& parent, const std::string& child) {
  return "  <joint name=\"" + name + "\" type=\"revolute\"><parent link=\"" + parent + "\"/><child link=\"" + child +
         "\"/><axis xyz=\"0 0 1\"/></joint>\n";
}

// ---- the XML itself

TEST(UrdfReader, MalformedXmlIsRefusedAtTheUnclosedTagSayingWhatWasExpected) {
  const std::string unclosed =
      "<robot name=\"r\">\n"
      "  <link name=\"base\">\n"
      "</robot>\n";
  expect_urdf_error(unclosed, {2, 3}, {"malformed XML", "<link>", "expected"});
  const std::string cut = "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link name=\"arm";
  expect_urdf_error(cut, {3, 3}, {"malformed XML", "expected"});
}

TEST(UrdfReader, ASecondDocumentElementIsRefusedAtIt) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           revolute("j", "base", "arm") + "</robot>\n<robot name=\"other\"/>\n";
  expect_urdf_error(urdf, place_of(urdf, "<robot name=\"other\""), {"expected"});
}

TEST(UrdfReader, ADocumentWithNoElementIsRefused) {
  expect_urdf_error("<?xml version=\"1.0\"?>\n<!-- nothing -->\n", {1, 1}, {"expected a <robot> element"});
}

TEST(UrdfReader, ARootElementOtherThanRobotIsRefusedAtItsTag) {
  const std::string urdf =
      "<?xml version=\"1.0\"?>\n"
      "  <sdf name=\"r\"><link name=\"base\"/></sdf>\n";
  expect_urdf_error(urdf, place_of(urdf, "<sdf"), {"<sdf>", "expected <robot>"});
}

TEST(UrdfReader, BillionLaughsIsRefusedAtItsDoctypeWithoutExpandingIt) {
  std::string urdf = "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [\n  <!ENTITY lol0 \"lol\">\n";
  for (int i = 1; i <= 9; ++i) {
    urdf += "  <!ENTITY lol" + std::to_string(i) + " \"";
    for (int k = 0; k < 10; ++k) urdf += "&lol" + std::to_string(i - 1) + ";";
    urdf += "\">\n";
  }
  urdf += "]>\n<robot name=\"&lol9;\"><link name=\"&lol9;\"/></robot>\n";
  // were the entities expanded, the name alone would take 3 GB: the test's time limit stops that
  expect_urdf_error(urdf, place_of(urdf, "<!DOCTYPE"), {"'DOCTYPE'", "not read", "expected a URDF without them"});
}

TEST(UrdfReader, AnExternalEntityIsRefusedAndNeverFetched) {
  const std::string urdf =
      "<?xml version=\"1.0\"?>\n"
      "<!DOCTYPE robot [ <!ENTITY secret SYSTEM \"file:///etc/passwd\"> ]>\n"
      "<robot name=\"r\"><link name=\"&secret;\"/></robot>\n";
  expect_urdf_error(urdf, {2, 1}, {"'DOCTYPE'", "fetch other files"});
}

TEST(UrdfReader, AnEntityDeclarationWithoutDoctypeIsRefusedAtItsPlace) {
  const std::string urdf =
      "<robot name=\"r\">\n"
      "  <link name=\"base\"/> <!ENTITY x SYSTEM \"http://example.com/x\">\n"
      "</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "<!ENTITY"), {"'ENTITY'", "expected a URDF without them"});
}

// (the column of XML errors is the test above's)
TEST(UrdfReader, DeeplyNestedElementsAreRefusedNotRecursedInto) {
  std::string urdf = "<robot name=\"r\"><link name=\"base\"/>\n";
  for (int i = 0; i < 100000; ++i) urdf += "<a>";
  for (int i = 0; i < 100000; ++i) urdf += "</a>";
  urdf += "\n</robot>\n";
  try {
    import_text(urdf);
    ADD_FAILURE() << "100,000 nested elements were read";
  } catch (const SourceError& e) {
    EXPECT_EQ(e.location().file, "robot.urdf");
    EXPECT_EQ(e.location().line, 2) << e.what();
    EXPECT_THAT(e.message(), HasSubstr("malformed XML"));
  }
}

// ---- names and the tree

TEST(UrdfReader, ALinkWithoutANameIsRefusedAtTheLink) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n    <link/>\n</robot>\n";
  expect_urdf_error(urdf, {3, 5}, {"<link> has no 'name' attribute"});
}

TEST(UrdfReader, AnEmptyLinkNameIsRefusedAtTheAttribute) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link   name=\"\"/>\n</robot>\n";
  expect_urdf_error(urdf, {3, 11}, {"'name' is empty"});
}

TEST(UrdfReader, ARobotWithoutLinksIsRefused) {
  expect_urdf_error("\n <robot name=\"r\"/>\n", {2, 2}, {"no <link>"});
}

TEST(UrdfReader, ADuplicateLinkNameIsRefusedAtTheSecondNamingTheFirst) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link name=\"arm\"/>\n"
                           "   <link name=\"base\"/>\n" +
                           revolute("j", "base", "arm") + "</robot>\n";
  expect_urdf_error(urdf, {4, 4}, {"link 'base' is declared twice", "first at line 2"});
}

TEST(UrdfReader, ADuplicateJointNameIsRefusedAtTheSecondNamingTheFirst) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           massive_link("hand") +
                           revolute("j", "base", "arm") + revolute("j", "arm", "hand") + "</robot>\n";
  expect_urdf_error(urdf, {6, 3}, {"joint 'j' is declared twice", "first at line 5"});
}

TEST(UrdfReader, AnUnknownJointTypeIsRefusedAtTheTypeAttribute) {
  const std::string urdf =
      "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
      "  <joint name=\"j\"\n         type=\"hinge\"><parent link=\"base\"/><child link=\"arm\"/></joint>\n</robot>\n";
  expect_urdf_error(urdf, {5, 10}, {"unknown type 'hinge'", "expected revolute, continuous, prismatic, fixed"});
}

TEST(UrdfReader, AJointWhoseParentOrChildIsNoLinkIsRefusedAtThatName) {
  const std::string parent = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                             "  <joint name=\"j\" type=\"fixed\"><parent link=\"bse\"/><child link=\"arm\"/></joint>\n"
                             "</robot>\n";
  expect_urdf_error(parent, place_of(parent, "link=\"bse\""), {"joint 'j': parent 'bse' is no link"});
  const std::string child = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                            "  <joint name=\"j\" type=\"fixed\"><parent link=\"base\"/><child link=\"amr\"/></joint>\n"
                            "</robot>\n";
  expect_urdf_error(child, place_of(child, "link=\"amr\""), {"joint 'j': child 'amr' is no link"});
}

TEST(UrdfReader, ALinkThatIsTheChildOfTwoJointsIsRefusedAtTheSecond) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("a") + massive_link("b") +
                           revolute("j1", "base", "a") + revolute("j2", "base", "b") +
                           "  <joint name=\"loop\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>"
                           "<axis xyz=\"0 0 1\"/></joint>\n</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "link=\"b\"/><axis xyz=\"0 0 1\"/></joint>\n</robot>"),
                    {"link 'b' is the child of two joints, 'j2' (line 6) and 'loop'", "expected one parent per link"});
}

TEST(UrdfReader, TwoRootsAreRefusedAtTheSecond) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           "  <link name=\"table\"/>\n" + revolute("j", "base", "arm") + "</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "<link name=\"table\""), {"links 'base' and 'table' are both roots"});
}

TEST(UrdfReader, JointsThatMakeACycleAreRefused) {
  // every link has a parent: no root at all
  const std::string ring = "<robot name=\"r\">\n" + massive_link("a") + massive_link("b") + revolute("ab", "a", "b") +
                           revolute("ba", "b", "a") + "</robot>\n";
  expect_urdf_error(ring, place_of(ring, "<joint name=\"ab\""), {"the joints 'ab' -> 'ba' -> 'ab' make a cycle", "expected a tree"});
  // a root, and a cycle beside it that the root does not reach
  const std::string beside = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("a") + massive_link("b") +
                             massive_link("c") + revolute("j", "base", "c") + revolute("ab", "a", "b") +
                             revolute("ba", "b", "a") + "</robot>\n";
  expect_urdf_error(beside, place_of(beside, "<joint name=\"ab\""),
                    {"the joints 'ab' -> 'ba' -> 'ab' make a cycle", "expected a tree"});
}

TEST(UrdfReader, ACycleErrorNamesAJointOnTheCycle) {
  const std::string ring = "<robot name=\"r\">\n" + massive_link("a") + massive_link("b") + massive_link("c") +
                           revolute("tail", "a", "c") + revolute("ab", "a", "b") + revolute("ba", "b", "a") +
                           "</robot>\n";
  expect_urdf_error(ring, place_of(ring, "<joint name=\"ab\""), {"cycle", "'ab'"});
  const std::string beside = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("a") + massive_link("b") +
                             massive_link("c") + massive_link("d") + revolute("j", "base", "d") +
                             revolute("tail", "a", "c") + revolute("ab", "a", "b") + revolute("ba", "b", "a") +
                             "</robot>\n";
  expect_urdf_error(beside, place_of(beside, "<joint name=\"ab\""), {"the joints 'ab' -> 'ba' -> 'ab' make a cycle"});
}

TEST(UrdfReader, AJointThatJoinsALinkToItselfIsRefusedAtItsChild) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           revolute("j", "base", "arm") + revolute("twist", "arm", "arm") + "</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "link=\"arm\"/><axis xyz=\"0 0 1\"/></joint>\n</robot>"),
                    {"joint 'twist' joins link 'arm' to itself"});
}

// ---- numbers

std::string arm_with_mass(const std::string& mass) {
  return "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link name=\"arm\">\n    <inertial>\n      <mass value=\"" +
         mass +
         "\"/>\n      <inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/>\n    "
         "</inertial>\n  </link>\n" +
         revolute("j", "base", "arm") + "</robot>\n";
}

TEST(UrdfReader, AWordWhereANumberBelongsIsRefusedAtItsAttribute) {
  for (const std::string word : {"heavy", "1,5", "0x10", "1e", "--1", "2kg"}) {
    SCOPED_TRACE(word);
    expect_urdf_error(arm_with_mass(word), {5, 13}, {"link 'arm': mass: '" + word + "' is not a number"});
  }
}

TEST(UrdfReader, NumbersThatAreNotFiniteAreRefusedAtTheirAttribute) {
  for (const std::string word : {"nan", "NaN", "inf", "-inf", "Infinity", "1e999", "-1e999"}) {
    SCOPED_TRACE(word);
    const std::string urdf = arm_with_mass(word);
    try {
      import_text(urdf);
      ADD_FAILURE() << "accepted";
    } catch (const SourceError& e) {
      EXPECT_EQ(e.location().line, 5);
      EXPECT_EQ(e.location().column, 13);
      EXPECT_THAT(e.message(), HasSubstr("'" + word + "' is not"));
    }
  }
  expect_urdf_error(arm_with_mass("1e999"), {5, 13}, {"'1e999' is not finite"});
}

TEST(UrdfReader, ANumberInAMultiLineStartTagIsPlacedAtItsAttribute) {
  const std::string urdf =
      "<robot name=\"r\">\n"
      "  <link name=\"base\"/>\n"
      "  <link name=\"arm\">\n"
      "    <inertial>\n"
      "      <mass value=\"1\"/>\n"
      "      <inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\"\n"
      "               iyy=\"0.1\" iyz=\"0\"\n"
      "               izz=\"nan\"/>\n"
      "    </inertial>\n"
      "  </link>\n" +
      revolute("j", "base", "arm") + "</robot>\n";
  expect_urdf_error(urdf, {8, 16}, {"link 'arm': izz: 'nan' is not a number"});
}

TEST(UrdfReader, WindowsLineEndingsPlaceErrorsOnTheSameLinesAndColumns) {
  std::string urdf = arm_with_mass("-2");
  for (std::size_t at = urdf.find('\n'); at != std::string::npos; at = urdf.find('\n', at + 2)) urdf.insert(at, "\r");
  expect_urdf_error(urdf, {5, 13}, {"the mass -2 is negative"});
}

TEST(UrdfReader, AnAttributeAfterAValueHoldingAGreaterThanSignIsPlacedAtItself) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           "  <joint name=\"a>b\" type=\"hinge\"><parent link=\"base\"/><child link=\"arm\"/></joint>\n"
                           "</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "type=\"hinge\""), {"joint 'a>b': unknown type 'hinge'"});
}

TEST(UrdfReader, ElementsOfOneNameOnOneLineArePlacedEachAtItsOwnTag) {
  const std::string urdf =
      "<robot name=\"r\"><link name=\"base\"/><link name=\"arm\"><inertial><origin xyz=\"0 0 0\"/><mass value=\"1\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial><visual><origin xyz=\"0 1\"/>"
      "<geometry><box size=\"1 1 1\"/></geometry></visual></link></robot>";
  expect_urdf_error(urdf, place_of(urdf, "xyz=\"0 1\""), {"link 'arm': visual origin xyz: '0 1' has 2 numbers"});
  const std::string joints =
      "<robot name=\"r\"><link name=\"base\"/><link name=\"arm\"/>"
      "<joint name=\"j\" type=\"fixed\"><parent link=\"base\"/><child link=\"arm\"/></joint>"
      "<joint name=\"k\" type=\"fixed\"><parent link=\"base\"/><child link=\"hand\"/></joint></robot>";
  expect_urdf_error(joints, place_of(joints, "link=\"hand\""), {"joint 'k': child 'hand' is no link"});
}

TEST(UrdfReader, ATripleWithTwoNumbersIsRefusedAtItsAttribute) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           "  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/>\n"
                           "    <origin rpy=\"0 0 0\" xyz=\"0 1\"/><axis xyz=\"0 0 1\"/></joint>\n</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "xyz=\"0 1\""), {"joint 'j' origin xyz: '0 1' has 2 numbers: expected three"});
}

TEST(UrdfReader, NumbersAsPublishedURDFsWriteThemImportAndParse) {
  const std::string urdf =
      "<robot name=\"r\">\n  <link name=\"base\"/>\n"
      "  <link name=\"arm\"><inertial><origin xyz=\".649262481663582 -.5 1.\" rpy=\"+1.0 0 0\"/>"
      "<mass value=\"1E-3\"/><inertia ixx=\"1.e-4\" ixy=\"0\" ixz=\"0\" iyy=\"+2E-4\" iyz=\"0\" izz=\".0002\"/>"
      "</inertial></link>\n"
      "  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/><origin xyz=\".25 +.5 1.\" "
      "rpy=\"-.5 .25 1E-1\"/><axis xyz=\"0 0 1.\"/><dynamics damping=\".5\"/></joint>\n"
      "</robot>\n";
  const Model model = imported_model(urdf);
  EXPECT_EQ(parameter(model, "arm_com_x"), 0.649262481663582);
  EXPECT_EQ(parameter(model, "arm_com_y"), -0.5);
  EXPECT_EQ(parameter(model, "arm_com_z"), 1.0);
  EXPECT_EQ(parameter(model, "arm_mass"), 1e-3);
  EXPECT_EQ(parameter(model, "arm_ixx"), 1e-4);
  EXPECT_EQ(parameter(model, "arm_iyy"), 2e-4);
  EXPECT_EQ(parameter(model, "arm_izz"), 2e-4);
  EXPECT_EQ(parameter(model, "j_damping"), 0.5);
  // the joint's origin: arm's origin at xyz and its axes those of Rz(0.1) Ry(0.25) Rx(-0.5), for
  // every angle of the joint (it turns about arm's own z)
  const ModelEquations eom = derive_equations(model);
  const NumericEquations at = evaluate_equations(model, eom, {{"j", 0.3}});
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.25, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const Eigen::Vector3d xyz(0.25, 0.5, 1.0);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(output(at, "arm_position_" + std::to_string(k + 1)), xyz(k), 1e-15);
    EXPECT_NEAR(output(at, "arm_axis_3_" + std::to_string(k + 1)), R(k, 2), 1e-15);
  }
}

TEST(UrdfReader, ASubnormalMassIsRefusedAtItsValueOrImportsIntoAModelThatParses) {
  const std::string urdf = arm_with_mass("1e-320");
  try {
    imported_model(urdf);
  } catch (const SourceError& e) {
    EXPECT_EQ(e.location().file, "robot.urdf") << e.what();
    EXPECT_EQ(e.location().line, 5) << e.what();
    EXPECT_EQ(e.location().column, 13) << e.what();
  }
}

// ---- masses and inertias

TEST(UrdfReader, ANegativeMassIsRefusedAtItsValue) {
  expect_urdf_error(arm_with_mass("-2"), {5, 13}, {"link 'arm': the mass -2 is negative"});
}

TEST(UrdfReader, AZeroMassWithAnInertiaIsRefusedAtTheMass) {
  expect_urdf_error(arm_with_mass("0"), {5, 13}, {"link 'arm': the mass is 0 but the inertia is not"});
}

std::string arm_with_inertia(const std::string& inertia) {
  return "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link name=\"upper_arm\">\n    <inertial>\n"
         "      <mass value=\"2\"/>\n      <inertia " +
         inertia + "/>\n    </inertial>\n  </link>\n" + revolute("j", "base", "upper_arm") + "</robot>\n";
}

TEST(UrdfReader, AnInertiaNoBodyHasIsRefusedNamingItsLink) {
  // 3 > 1 + 1: A + B >= C broken
  const std::string urdf = arm_with_inertia("ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"3\"");
  expect_urdf_error(urdf, {6, 7}, {"link 'upper_arm'", "3 exceeds the sum of the other two", "--repair-inertia"});
}

TEST(UrdfReader, RepairInertiaReplacesItListsItAndTheModelPassesEomgensOwnCheck) {
  const std::string urdf = arm_with_inertia("ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"3\"");
  ImportOptions repair;
  repair.repair_inertia = true;
  const ImportResult result = import_text(urdf, repair);
  ASSERT_EQ(result.repairs.size(), 1u);
  EXPECT_THAT(result.repairs[0], HasSubstr("link 'upper_arm'"));
  EXPECT_THAT(result.repairs[0], HasSubstr("1.5, 1.5, 3"));
  EXPECT_THAT(result.text, HasSubstr("# --repair-inertia: link 'upper_arm'"));
  const Model model = parse_model(result.text, "robot.urdf (as imported)");
  EXPECT_NEAR(parameter(model, "upper_arm_ixx"), 1.5, 1e-15);
  EXPECT_NEAR(parameter(model, "upper_arm_iyy"), 1.5, 1e-15);
  EXPECT_NEAR(parameter(model, "upper_arm_izz"), 3, 1e-15);
}

TEST(UrdfReader, ARankOnePlaceholderInertiaIsRefusedAndRepairable) {
  const std::string urdf = arm_with_inertia("ixx=\"1e-6\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"");
  expect_urdf_error(urdf, {6, 7}, {"link 'upper_arm'", "1e-06 exceeds the sum of the other two"});
  ImportOptions repair;
  repair.repair_inertia = true;
  const ImportResult result = import_text(urdf, repair);
  ASSERT_EQ(result.repairs.size(), 1u);
  EXPECT_THAT(result.repairs[0], HasSubstr("5e-07, 5e-07, 1e-06"));
  const Model model = parse_model(result.text, "robot.urdf (as imported)");
  EXPECT_NEAR(parameter(model, "upper_arm_ixx"), 1e-6, 1e-21);
  EXPECT_NEAR(parameter(model, "upper_arm_iyy"), 5e-7, 1e-21);
  EXPECT_NEAR(parameter(model, "upper_arm_izz"), 5e-7, 1e-21);
}

TEST(UrdfReader, ANegativeDefiniteInertiaIsRefusedAndRepairedToOneThatParses) {
  const std::string urdf =
      arm_with_inertia("ixx=\"-0.1\" ixy=\"0.02\" ixz=\"0\" iyy=\"0.2\" iyz=\"0.01\" izz=\"0.15\"");
  expect_urdf_error(urdf, {6, 7}, {"link 'upper_arm'", "a principal moment is negative"});
  ImportOptions repair;
  repair.repair_inertia = true;
  EXPECT_NO_THROW(imported_model(urdf, repair));
}

// ---- joints

std::string joint_with_axis(const std::string& type, const std::string& axis) {
  return "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") + "  <joint name=\"j\" type=\"" + type +
         "\">\n    <parent link=\"base\"/><child link=\"arm\"/>\n    <axis xyz=\"" + axis +
         "\"/>\n  </joint>\n</robot>\n";
}

TEST(UrdfReader, AZeroAxisIsRefusedOnARevoluteAndAPrismaticJoint) {
  for (const std::string type : {"revolute", "continuous", "prismatic", "planar"}) {
    SCOPED_TRACE(type);
    expect_urdf_error(joint_with_axis(type, "0 0 0"), {6, 11}, {"joint 'j': the axis has zero length", type});
  }
}

TEST(UrdfReader, AFixedJointWithAZeroAxisIsAccepted) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           massive_link("hand") +
                           revolute("j", "base", "arm") +
                           "  <joint name=\"weld\" type=\"fixed\"><parent link=\"arm\"/><child link=\"hand\"/>"
                           "<axis xyz=\"0 0 0\"/></joint>\n</robot>\n";
  EXPECT_EQ(coordinate_names(imported_model(urdf)), std::vector<std::string>{"j"});
}

TEST(UrdfReader, NegativeDampingIsRefusedAtItsAttribute) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           "  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/>\n"
                           "    <axis xyz=\"0 0 1\"/><dynamics friction=\"0.1\" damping=\"-0.5\"/></joint>\n</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "damping=\"-0.5\""), {"joint 'j': the damping -0.5 is negative"});
}

std::string mimic_robot(const std::string& leader, const std::string& leader_type) {
  return "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("left") + massive_link("right") +
         "  <joint name=\"lead\" type=\"" + leader_type +
         "\"><parent link=\"base\"/><child link=\"left\"/><axis xyz=\"0 1 0\"/></joint>\n"
         "  <joint name=\"follow\" type=\"prismatic\"><parent link=\"base\"/><child link=\"right\"/>"
         "<axis xyz=\"0 1 0\"/>\n    <mimic joint=\"" +
         leader + "\" multiplier=\"-1\"/></joint>\n</robot>\n";
}

TEST(UrdfReader, AMimicOfAnUnknownJointOfItselfOrOfAFixedJointIsRefusedAtTheMimic) {
  expect_urdf_error(mimic_robot("leed", "prismatic"), {7, 5}, {"joint 'follow' mimics 'leed', which is no joint"});
  expect_urdf_error(mimic_robot("follow", "prismatic"), {7, 5}, {"joint 'follow' mimics itself"});
  expect_urdf_error(mimic_robot("lead", "fixed"), {7, 5},
                    {"joint 'follow' (prismatic) mimics 'lead' (fixed)", "expected both revolute, continuous or prismatic"});
}

TEST(UrdfReader, AMimicOfAMovingJointImportsAsAConstraint) {
  const Model model = imported_model(mimic_robot("lead", "prismatic"));
  EXPECT_EQ(coordinate_names(model), (std::vector<std::string>{"lead", "follow"}));
  ASSERT_EQ(model.system.constraints().size(), 1u);
  EXPECT_EQ(model.system.constraints()[0].name, "follow_mimic");
}

TEST(UrdfReader, JointsThatMimicEachOtherAreRefusedAtTheFirstMimic) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("left") +
                           massive_link("right") +
                           "  <joint name=\"lead\" type=\"prismatic\"><parent link=\"base\"/><child link=\"left\"/>"
                           "<axis xyz=\"0 1 0\"/>\n    <mimic joint=\"follow\"/></joint>\n"
                           "  <joint name=\"follow\" type=\"prismatic\"><parent link=\"base\"/><child link=\"right\"/>"
                           "<axis xyz=\"0 1 0\"/>\n    <mimic joint=\"lead\"/></joint>\n</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "<mimic joint=\"follow\""), {"mimic", "'lead'", "'follow'"});
}

TEST(UrdfReader, APlanarJointWithANonPrincipalAxisIsRefusedAtTheAxis) {
  expect_urdf_error(joint_with_axis("planar", "0 1 1"), {6, 11},
                    {"joint 'j' (planar): the axis [0, 1, 1] is not along x, y or z", "expected a principal axis"});
}

TEST(UrdfReader, APlanarJointAlongAPrincipalAxisImportsWithThreeCoordinates) {
  const Model model = imported_model(joint_with_axis("planar", "0 0 -2"));
  EXPECT_EQ(coordinate_names(model), (std::vector<std::string>{"j_x", "j_y", "j_theta"}));
}

TEST(UrdfReader, AMovingJointThatMovesOnlyMasslessLinksIsRefusedAtTheJoint) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           "  <link name=\"tool\"/>\n  <link name=\"tip\"><inertial><mass value=\"0\"/>"
                           "<inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/>"
                           "</inertial></link>\n" +
                           revolute("shoulder", "base", "arm") + revolute("wrist", "arm", "tool") +
                           "  <joint name=\"tcp\" type=\"fixed\"><parent link=\"tool\"/><child link=\"tip\"/></joint>\n"
                           "</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "<joint name=\"wrist\""),
                    {"joint 'wrist' (revolute) moves only links without mass ('tool'", "expected a mass beyond"});
}

TEST(UrdfReader, ARobotWithNoMovingJointIsRefusedAtTheRobot) {
  const std::string single = "<robot name=\"r\">\n  <link name=\"base\"/>\n</robot>\n";
  expect_urdf_error(single, {1, 1}, {"joint", "expected"});
  const std::string welded = "\n<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                             "  <joint name=\"j\" type=\"fixed\"><parent link=\"base\"/><child link=\"arm\"/></joint>\n"
                             "</robot>\n";
  expect_urdf_error(welded, {2, 1}, {"joint", "expected"});
}

TEST(UrdfReader, ARevoluteJointThatTurnsOnlyAPointMassOnItsAxisIsRefusedAtTheJoint) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n"
                           "  <link name=\"arm\"><inertial><mass value=\"1\"/>"
                           "<inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/>"
                           "</inertial></link>\n" +
                           revolute("j", "base", "arm") + "</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "<joint name=\"j\""), {"joint 'j'", "mass matrix"});
}

// ---- names as identifiers of the model

TEST(UrdfReader, NamesThatCollideOnceMadeIdentifiersAreRefusedAtTheSecond) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("a-b") + massive_link("a_b") +
                           revolute("j1", "base", "a-b") + revolute("j2", "base", "a_b") + "</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "<link name=\"a_b\""),
                    {"link 'a_b' becomes the name 'a_b' in the model, which link 'a-b' (line 3) already has"});
}

TEST(UrdfReader, ALinkNamedAfterAGeneratedNameCollidesWithIt) {
  // link 'arm' has the parameter arm_mass
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                           massive_link("arm_mass") + revolute("j1", "base", "arm") +
                           revolute("j2", "base", "arm_mass") + "</robot>\n";
  expect_urdf_error(urdf, place_of(urdf, "<link name=\"arm_mass\""), {"becomes the name 'arm_mass'"});
}

TEST(UrdfReader, LinksAndJointsNamedLikeKeywordsImportAndParse) {
  const std::string urdf = "<robot name=\"model\">\n  <link name=\"frame\"/>\n" + massive_link("body") +
                           massive_link("point") + massive_link("a") + revolute("end", "frame", "body") +
                           revolute("for", "body", "point") + revolute("t", "point", "a") + "</robot>\n";
  const Model model = imported_model(urdf);
  EXPECT_EQ(coordinate_names(model), (std::vector<std::string>{"end_", "for_", "t_"}));
  EXPECT_EQ(model.system.rigid_bodies().size(), 3u);
}

TEST(UrdfReader, AJointNamedLikeALinkGetsACoordinateEndingInQ) {
  const std::string urdf = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("elbow") +
                           revolute("elbow", "base", "elbow") + "</robot>\n";
  const Model model = imported_model(urdf);
  EXPECT_EQ(coordinate_names(model), std::vector<std::string>{"elbow_q"});
}

TEST(UrdfReader, NamesWithCharactersOutsideIdentifiersImportAndParse) {
  const std::string urdf = "<robot name=\"my robot\">\n  <link name=\"base link\"/>\n" + massive_link("2nd/arm.link") +
                           massive_link("\xc3\xa9paule") + revolute("1st joint", "base link", "2nd/arm.link") +
                           revolute("j-2", "2nd/arm.link", "\xc3\xa9paule") + "</robot>\n";
  const Model model = imported_model(urdf);
  EXPECT_EQ(coordinate_names(model), (std::vector<std::string>{"_1st_joint", "j_2"}));
}

// ---- size and cost

TEST(UrdfReader, AFileOverTheSizeLimitIsRefusedBeforeItIsRead) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("eomgen_urdf_reader_test_" + std::to_string(::getpid()) + ".urdf");
  const std::string robot = "<robot name=\"r\">\n  <link name=\"base\"/>\n" + massive_link("arm") +
                            revolute("j", "base", "arm") + "</robot>\n";
  // just within the limit: read; one byte more: refused
  std::string text = robot + "<!--" + std::string(urdf::max_urdf_bytes - robot.size() - 7, 'x') + "-->";
  ASSERT_EQ(text.size(), urdf::max_urdf_bytes);
  std::ofstream(path, std::ios::binary) << text;
  EXPECT_NO_THROW(urdf::import_urdf(path.string()));
  text.insert(robot.size(), " ");
  std::ofstream(path, std::ios::binary) << text;
  try {
    urdf::import_urdf(path.string());
    ADD_FAILURE() << "a file of " << text.size() << " bytes was read";
  } catch (const SourceError& e) {
    EXPECT_EQ(e.location().file, path.string());
    EXPECT_EQ(e.location().line, 1);
    EXPECT_EQ(e.location().column, 1);
    EXPECT_THAT(e.message(), HasSubstr("more than 8 MiB"));
  }
  std::filesystem::remove(path);
}

// A chain l0 - l1 - ... - ln joined by revolute joints, one element per line; the joints in file
// order or child first; the links without mass, or each with one.
std::string chain(int n, bool child_first, bool massive = false) {
  const auto link = [](int i) { return "l" + std::to_string(i); };
  std::string urdf = "<robot name=\"r\">\n  <link name=\"l0\"/>\n";
  for (int i = 1; i <= n; ++i) urdf += massive ? massive_link(link(i)) : "  <link name=\"" + link(i) + "\"/>\n";
  for (int k = 0; k < n; ++k) {
    const int i = child_first ? n - k : k + 1;
    urdf += revolute("j" + std::to_string(i), link(i - 1), link(i));
  }
  return urdf + "</robot>\n";
}

// A file within the size limit is read and written in time linear in its size: the worst
// shapes for a reader that walks lines, siblings or the tree anew (one line, joints child first,
// a chain of massless links but the last, as deep as the limit allows) in one file, which runs
// past the test's time limit if any of them costs the square of the size.
TEST(UrdfReader, TheWorstShapedFileWithinTheSizeLimitIsReadAndWrittenInOnePass) {
  std::string urdf = chain(28000, /*child_first=*/true);
  const std::string last = "  <link name=\"l28000\"/>\n";
  urdf.replace(urdf.find(last), last.size(), massive_link("l28000"));
  urdf.erase(std::remove(urdf.begin(), urdf.end(), '\n'), urdf.end());
  ASSERT_LT(urdf.size(), urdf::max_urdf_bytes);
  const urdf::Robot robot = urdf::read_robot(urdf, "robot.urdf");
  EXPECT_EQ(robot.joints.size(), 28000u);
  const ImportResult result = urdf::write_model(robot);
  EXPECT_THAT(result.text, HasSubstr("coordinate j28000"));
}

TEST(UrdfReader, AChainJustWithinTheSizeLimitImportsWithoutExhaustingTheStack) {
  const std::string urdf = chain(30000, false, true);
  ASSERT_LT(urdf.size(), urdf::max_urdf_bytes);
  try {
    const ImportResult result = import_text(urdf);
    EXPECT_THAT(result.text, HasSubstr("coordinate j30000"));
  } catch (const SourceError& e) {
    EXPECT_EQ(e.location().file, "robot.urdf") << e.what();
  }
}

}  // namespace
}  // namespace eomgen
