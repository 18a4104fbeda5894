#include "eomgen/report/equation_printer.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include "eomgen/base/error.hpp"
#include "support/expect_throw.hpp"
#include "support/test_models.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using ::testing::HasSubstr;
using ::testing::Not;

// theta from the downward vertical a1; bob of mass m on a massless rod of length l
Model simple_pendulum() {
  Model model;
  model.name = "pendulum";
  model.description = "Simple pendulum";
  MechanicalSystem& s = model.system;
  const Coordinate theta = s.add_coordinate("theta");
  const ex m = s.add_parameter("m", 1.0, "kg"), l = s.add_parameter("l", 0.5, "m");
  const ex g = s.add_parameter("g", 9.81, "m/s^2");
  const FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, theta.q));
  s.add_particle("bob", m, s.add_point("p", s.origin(), Vector(b, l, 0, 0)));
  s.set_gravity(Vector(s.inertial_frame(), g, 0, 0));
  model.outputs.push_back(Output{"height", {l * GiNaC::cos(theta.q)}, {"height"}, {}});
  return model;
}

Model double_pendulum() { return testing::double_pendulum_model(); }

Model cartesian_pendulum() { return testing::cartesian_pendulum_model(); }

// a knife edge sliding in the plane: no velocity across the blade
Model knife_edge() {
  Model model;
  model.name = "knife_edge";
  MechanicalSystem& s = model.system;
  const Coordinate x = s.add_coordinate("x"), y = s.add_coordinate("y"), psi = s.add_coordinate("psi");
  const ex m = s.add_parameter("m", 1.0, "kg"), J = s.add_parameter("J", 0.1, "kg*m^2");
  const FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, psi.q));
  GiNaC::matrix inertia(3, 3);
  inertia(0, 0) = J;
  inertia(1, 1) = J;
  inertia(2, 2) = J;
  s.add_rigid_body("blade", m, s.add_point("c", s.origin(), Vector(s.inertial_frame(), x.q, y.q, 0)), b, inertia);
  s.add_nonholonomic_constraint("no_slip", -x.qd * GiNaC::sin(psi.q) + y.qd * GiNaC::cos(psi.q));
  return model;
}

// n rods pinned end to end (the benchmark's planar chain, smaller inertia details)
Model planar_chain(int n) {
  Model model;
  model.name = "chain";
  MechanicalSystem& s = model.system;
  const ex m = s.add_parameter("m", 2.0, "kg"), l = s.add_parameter("l", 0.5, "m");
  s.set_gravity(Vector(s.inertial_frame(), s.add_parameter("g", 9.81, "m/s^2"), 0, 0));
  FrameId frame = s.inertial_frame();
  PointId joint = s.origin();
  for (int i = 1; i <= n; ++i) {
    const Coordinate q = s.add_coordinate("q" + std::to_string(i));
    frame = s.add_frame("b" + std::to_string(i), frame, Rotation::principal(3, q.q));
    GiNaC::matrix J(3, 3);
    J(0, 0) = m * l * l / 1200;
    J(1, 1) = m * l * l / 12;
    J(2, 2) = m * l * l / 12;
    s.add_rigid_body("rod" + std::to_string(i), m, s.add_point("c" + std::to_string(i), joint, Vector(frame, l / 2, 0, 0)),
                     frame, J);
    joint = s.add_point("j" + std::to_string(i), joint, Vector(frame, l, 0, 0));
  }
  return model;
}

std::string print(const Model& model, PrintOptions options = {}) {
  return format_equations(model, derive_equations(model), options);
}

PrintOptions with_format(EquationFormat format) {
  PrintOptions options;
  options.format = format;
  return options;
}

TEST(TextOutput, SimplePendulumIsTheHandDerivation) {
  EXPECT_EQ(print(simple_pendulum()),
            "Model pendulum: Simple pendulum\n"
            "\n"
            "Coordinates (n = 1): theta\n"
            "Parameters:\n"
            "  m = 1 [kg]\n"
            "  l = 0.5 [m]\n"
            "  g = 9.81 [m/s^2]\n"
            "Inputs: none\n"
            "Constraints (m = 0): none\n"
            "\n"
            "M(q) qdd = F(q, qd, t, u) + Xi^T lambda\n"
            "\n"
            "Mass matrix M (1 x 1, symmetric: upper triangle shown)\n"
            "  M[1,1] = m*l^2\n"
            "\n"
            "Forcing F (1 x 1)\n"
            "  F[1] = -m*l*g*sin(theta)\n"
            "\n"
            "Kinetic energy\n"
            "  T = m*l^2*theta_dot^2/2\n"
            "\n"
            "Potential energy\n"
            "  V = -m*l*g*cos(theta)\n"
            "\n"
            "Outputs\n"
            "  height = l*cos(theta)\n");
}

TEST(TextOutput, DoublePendulumPrintsTheUpperTriangleOfTheSymmetricMassMatrix) {
  const std::string text = print(double_pendulum());
  EXPECT_THAT(text, HasSubstr("Mass matrix M (2 x 2, symmetric: upper triangle shown)\n"));
  EXPECT_THAT(text, HasSubstr("  M[1,1] = m1*l1^2 + m2*l1^2 + 2*m2*l1*l2*cos(q2) + m2*l2^2\n"));
  EXPECT_THAT(text, HasSubstr("  M[1,2] = m2*l1*l2*cos(q2) + m2*l2^2\n"));
  EXPECT_THAT(text, HasSubstr("  M[2,2] = m2*l2^2\n"));
  EXPECT_THAT(text, Not(HasSubstr("M[2,1]")));
  // the two relative rotations about one axis are one rotation by q1 + q2
  EXPECT_THAT(text, HasSubstr("  F[2] = -m2*l1*l2*q1_dot^2*sin(q2) - m2*l2*g*sin(q1 + q2)\n"));
  EXPECT_THAT(text, Not(HasSubstr("Xi[")));  // no constraint sections without constraints
}

TEST(TextOutput, HolonomicConstraintGivesJacobianBiasAndResidual) {
  const std::string text = print(cartesian_pendulum());
  EXPECT_THAT(text, HasSubstr("Constraints (m = 1):\n  1. rod (holonomic)\n"));
  EXPECT_THAT(text, HasSubstr("M(q) qdd = F(q, qd, t, u) + Xi^T lambda, Xi qd + Xi_t = 0\n"));
  EXPECT_THAT(text, HasSubstr("  Xi[1,1] = 2*x\n  Xi[1,2] = 2*y\n"));
  EXPECT_THAT(text, HasSubstr("  Xi_t[1] = 0\n"));
  // d/dt (2 x xd + 2 y yd) at qdd = 0
  EXPECT_THAT(text, HasSubstr("  b[1] = 2*x_dot^2 + 2*y_dot^2\n"));
  EXPECT_THAT(text, HasSubstr("  phi[1] = -l^2 + x^2 + y^2\n"));
  EXPECT_THAT(text, HasSubstr("(rows: 1 = rod)"));
}

TEST(TextOutput, NonholonomicConstraintHasNoResidualSection) {
  const std::string text = print(knife_edge());
  EXPECT_THAT(text, HasSubstr("  1. no_slip (nonholonomic)\n"));
  EXPECT_THAT(text, HasSubstr("  Xi[1,1] = -sin(psi)\n  Xi[1,2] = cos(psi)\n  Xi[1,3] = 0\n"));
  EXPECT_THAT(text, HasSubstr("  b[1] = -x_dot*psi_dot*cos(psi) - y_dot*psi_dot*sin(psi)\n"));
  EXPECT_THAT(text, Not(HasSubstr("phi[")));
}

TEST(PartSelection, PrintsOnlyTheNamedParts) {
  PrintOptions options;
  options.parts = parse_equation_parts("M,T");
  const std::string text = print(cartesian_pendulum(), options);
  EXPECT_THAT(text, HasSubstr("M[1,1] = m"));
  EXPECT_THAT(text, HasSubstr("T = "));
  for (const char* absent : {"F[1]", "Xi[", "Xi_t[", "b[", "phi[", "V = "})
    EXPECT_THAT(text, Not(HasSubstr(absent)));
  options.parts = parse_equation_parts("b,outputs");
  EXPECT_THAT(print(simple_pendulum(), options), HasSubstr("height = l*cos(theta)"));
}

TEST(PartSelection, UnknownOrEmptyListIsAnErrorListingTheKeys) {
  EXPECT_THROW_MESSAGE(parse_equation_parts("M,Q"), Error,
                       "selecting parts to print: unknown part 'Q'; accepted: M, F, Xi, Xi_t, b, phi, T, V, outputs, tau, g, C, J, regressor");
  EXPECT_THROW_MESSAGE(parse_equation_parts(""), Error,
                       "selecting parts to print: the list is empty; accepted: M, F, Xi, Xi_t, b, phi, T, V, outputs, tau, g, C, J, regressor");
  EXPECT_THROW_MESSAGE(parse_equation_parts("M,,F"), Error,
                       "selecting parts to print: unknown part ''; accepted: M, F, Xi, Xi_t, b, phi, T, V, outputs, tau, g, C, J, regressor");
}

TEST(SharedForm, ListsEveryUsedIntermediateOnceInOrder) {
  PrintOptions options;
  options.intermediates = IntermediateForm::shared;
  const std::string text = print(double_pendulum(), options);
  const auto where = text.find("\nwhere (");
  ASSERT_NE(where, std::string::npos);
  // each z used anywhere is defined exactly once, definitions in increasing order
  const std::regex use("z([0-9]+)"), definition("\n  z([0-9]+) = ");
  std::set<int> used, defined;
  for (std::sregex_iterator it(text.begin(), text.end(), use), end; it != end; ++it) used.insert(std::stoi((*it)[1]));
  int previous = 0;
  for (std::sregex_iterator it(text.begin() + static_cast<long>(where), text.end(), definition), end; it != end; ++it) {
    const int k = std::stoi((*it)[1]);
    EXPECT_GT(k, previous);
    previous = k;
    defined.insert(k);
  }
  EXPECT_FALSE(used.empty());
  EXPECT_EQ(used, defined);
}

TEST(SharedForm, ChosenAutomaticallyForLargeSystemsOnly) {
  const Model pendulum = simple_pendulum(), chain = planar_chain(13);  // above the local form's limit
  const ModelEquations small = derive_equations(pendulum), large = derive_equations(chain);
  PrintOptions options;
  EXPECT_LT(written_out_size(pendulum, small, options.parts), 100);
  EXPECT_FALSE(uses_shared_form(pendulum, small, options));
  EXPECT_GT(written_out_size(chain, large, options.parts), options.max_written_out_size);
  EXPECT_TRUE(uses_shared_form(chain, large, options));
  EXPECT_THAT(format_equations(chain, large, options), HasSubstr("\nwhere ("));
  // the other threshold: a small model with intermediates
  const Model three = planar_chain(3);
  const ModelEquations few = derive_equations(three);
  ASSERT_GT(few.subexpressions.size(), 0u);
  EXPECT_FALSE(uses_shared_form(three, few, options));
  options.max_intermediates = few.subexpressions.size() - 1;
  EXPECT_TRUE(uses_shared_form(three, few, options));
  options.intermediates = IntermediateForm::written_out;
  EXPECT_FALSE(uses_shared_form(chain, large, options));
}

TEST(SharedForm, ChosenWhenMultiplyingOutWouldBeLargeThoughTheTreeIsSmall) {
  // V = (q1 + ... + q8)^8 is a tree of a dozen nodes and 8^8 = 16.7 million terms multiplied out
  Model model;
  model.name = "octic";
  MechanicalSystem& s = model.system;
  GiNaC::exvector coordinates;
  for (int i = 1; i <= 8; ++i) coordinates.push_back(s.add_coordinate("q" + std::to_string(i)).q);
  s.add_potential("octic", GiNaC::pow(GiNaC::add(coordinates), 8));
  const ModelEquations eom = derive_equations(model);
  PrintOptions options;
  options.parts = parse_equation_parts("V");
  EXPECT_LT(written_out_size(model, eom, options.parts), 20);
  EXPECT_GT(multiplied_out_size(model, eom, options.parts), 8 * std::pow(8.0, 8));
  EXPECT_TRUE(uses_shared_form(model, eom, options));
  EXPECT_THAT(format_equations(model, eom, options), HasSubstr("V = (q1 + q2 + q3 + q4 + q5 + q6 + q7 + q8)^8\n"));
  // a square of the same sum multiplies out to 64 terms and is written out
  Model square;
  square.name = "square";
  GiNaC::exvector q;
  for (int i = 1; i <= 8; ++i) q.push_back(square.system.add_coordinate("q" + std::to_string(i)).q);
  square.system.add_potential("square", GiNaC::pow(GiNaC::add(q), 2));
  EXPECT_FALSE(uses_shared_form(square, derive_equations(square), options));
}

TEST(Determinism, SameModelPrintsTheSameBytesWhateverSymbolsCameBefore) {
  for (EquationFormat format : {EquationFormat::text, EquationFormat::latex, EquationFormat::markdown}) {
    const std::string first = print(double_pendulum(), with_format(format));
    std::vector<GiNaC::realsymbol> dummies;
    for (int i = 0; i < 500; ++i) dummies.emplace_back("dummy" + std::to_string(i));
    EXPECT_EQ(print(double_pendulum(), with_format(format)), first);
    PrintOptions shared = with_format(format);
    shared.intermediates = IntermediateForm::shared;
    EXPECT_EQ(print(planar_chain(3), shared), print(planar_chain(3), shared));
  }
}

TEST(LatexOutput, IsACompleteDocumentWithOneAlignedRowPerEntry) {
  Model model = simple_pendulum();
  model.name = "my_pendulum";
  const std::string tex = print(model, with_format(EquationFormat::latex));
  EXPECT_EQ(tex.rfind("\\documentclass", 0), 0u);
  EXPECT_THAT(tex, HasSubstr("\\usepackage{amsmath}\n"));
  EXPECT_THAT(tex, HasSubstr("\\section*{Equations of motion: my\\_pendulum}"));
  EXPECT_THAT(tex, HasSubstr("$g = 9.81$~m/s\\^{}2"));
  EXPECT_THAT(tex, HasSubstr("  M_{1,1} &= m l^{2}\n"));
  EXPECT_THAT(tex, HasSubstr("  F_{1} &= -m l g \\sin(\\theta)\n"));
  EXPECT_THAT(tex, HasSubstr("  T &= \\frac{m l^{2} \\dot{\\theta}^{2}}{2}\n"));
  EXPECT_THAT(tex, HasSubstr("  \\text{height} &= l \\cos(\\theta)\n"));
  EXPECT_EQ(std::count(tex.begin(), tex.end(), '{'), std::count(tex.begin(), tex.end(), '}'));
  const std::regex begin("\\\\begin\\{"), end("\\\\end\\{");
  EXPECT_EQ(std::distance(std::sregex_iterator(tex.begin(), tex.end(), begin), std::sregex_iterator()),
            std::distance(std::sregex_iterator(tex.begin(), tex.end(), end), std::sregex_iterator()));
  EXPECT_EQ(tex.substr(tex.size() - 15), "\\end{document}\n");
}

TEST(LatexOutput, LongEntriesContinueOnFurtherRows) {
  PrintOptions options = with_format(EquationFormat::latex);
  options.parts = parse_equation_parts("F");
  const std::string tex = print(planar_chain(3), options);
  EXPECT_THAT(tex, HasSubstr(" \\\\\n  &\\quad + "));
}

// Compiles the documents with pdflatex when it is installed (Debian: texlive-latex-base).
TEST(LatexOutput, CompilesWithPdflatex) {
  ASSERT_EQ(std::system("command -v pdflatex > /dev/null 2>&1"), 0) << "pdflatex is missing: run scripts/install-deps.sh";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("eomgen_latex_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  PrintOptions shared = with_format(EquationFormat::latex);
  shared.intermediates = IntermediateForm::shared;
  const std::pair<std::string, std::string> documents[] = {
      {"double_pendulum", print(double_pendulum(), with_format(EquationFormat::latex))},
      {"cartesian", print(cartesian_pendulum(), with_format(EquationFormat::latex))},
      {"knife_edge", print(knife_edge(), with_format(EquationFormat::latex))},
      {"chain_shared", print(planar_chain(4), shared)},
  };
  for (const auto& [name, tex] : documents) {
    std::ofstream(dir / (name + ".tex")) << tex;
    const std::string command = "cd '" + dir.string() + "' && pdflatex -interaction=nonstopmode -halt-on-error " +
                                name + ".tex > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << "see " << (dir / (name + ".log")).string();
    EXPECT_TRUE(std::filesystem::exists(dir / (name + ".pdf"))) << name;
  }
  if (!HasFailure()) std::filesystem::remove_all(dir);
}

TEST(MarkdownOutput, HeadingsAndFencedBlocks) {
  const std::string md = print(cartesian_pendulum(), with_format(EquationFormat::markdown));
  EXPECT_EQ(md.rfind("# Equations of motion: cartesian_pendulum\n", 0), 0u);
  EXPECT_THAT(md, HasSubstr("| `m` | 2 | kg |\n"));
  EXPECT_THAT(md, HasSubstr("\n## Mass matrix M (2 x 2, symmetric: upper triangle shown)\n\n```text\nM[1,1] = m\nM[1,2] = 0\nM[2,2] = m\n```\n"));
  EXPECT_THAT(md, HasSubstr("```text\nphi[1] = -l^2 + x^2 + y^2\n```\n"));
  const std::regex fence("```");
  EXPECT_EQ(std::distance(std::sregex_iterator(md.begin(), md.end(), fence), std::sregex_iterator()) % 2, 0);
}

}  // namespace
}  // namespace eomgen
